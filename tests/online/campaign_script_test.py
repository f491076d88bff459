#!/usr/bin/env python3
"""host_tools/online/analysis/campaign.py on the fixture runs (tests/online/fixtures/): the 5-NN
chart column is read from the final round's codes table only. Reading round 6's table of a run
whose final model is round 12 would report the wrong model's code; this test fails if that can
happen.

  python3 tests/online/campaign_script_test.py REPO_ROOT
"""
import os, shutil, tempfile

from script_checks import check, finish, fixtures, table


def run(*dirs):
    return table("campaign.py", *dirs)


with tempfile.TemporaryDirectory() as tmp:
    # A run whose last round is 6: its codes_round_6.txt is the final model's table.
    gs = os.path.join(tmp, "gs_seed3")
    shutil.copytree(os.path.join(fixtures, "gs_seed3"), gs)
    out, rows = run(gs)
    check("round-6 run: chart column read from codes_round_6.txt", rows[0][-1] == "z2,z3: yes")
    check("round-6 run: mean ratio is the run's (.556)", "mean ratio at 9,666 0.556" in out)
    check("round-6 run: the verdict names z2, z3 by the linear rule too", rows[0][6] == "z2,z3" and rows[0][7] == "yes / yes")

    # A run whose last round is 12, with its final table: read.
    r500 = os.path.join(tmp, "r500_seed0")
    shutil.copytree(os.path.join(fixtures, "r500_seed0"), r500)
    _, rows = run(r500)
    check("round-12 run: chart column read from codes_round_12.txt", rows[0][-1] == "z2,z3: no")

    # The same run with only an earlier round's table (a mid-run model): not read.
    os.rename(os.path.join(r500, "codes_round_12.txt"), os.path.join(r500, "codes_round_6.txt"))
    _, rows = run(r500)
    check("round-12 run with only round 6's table: chart column 'not computed'", rows[0][-1] == "not computed")

    # Two runs together: one row each, mean over both.
    out, rows = run(gs, r500)
    check("two runs: two rows", len(rows) == 2)
    check("two runs: mean of .556 and .554", "mean ratio at 9,666 0.555" in out)

finish()
