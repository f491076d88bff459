#!/usr/bin/env bash
# Bad files where the programs expect files, refused with one line naming the file and the
# reason, and nothing written through them: a journal that is a symbolic link (with --replace:
# the link's target stays as it was), a FIFO or /dev/zero; a float model that is /dev/zero
# (it once grew without bound); a meta JSON of another model (its KL order would go into the
# header); a bad number (--noise inf) named by its option.
# Usage: bad_files.sh WORK_DIR curio-controller curio-quantize [curio-lab]
set -u
work=$1 controller=$2 quantize=$3 lab=${4:-}
rm -rf "$work" && mkdir -p "$work"
failures=0

# expect NAME EXPECTED_TEXT CMD...: the command exits non-zero within 20 s and its stderr
# contains EXPECTED_TEXT.
expect() {
  local name=$1 text=$2
  shift 2
  local err="$work/$name.err"
  timeout 20 "$@" >/dev/null 2>"$err"
  local rc=$?
  if [[ $rc -eq 0 || $rc -eq 124 ]] || ! grep -qF -- "$text" "$err"; then
    echo "FAIL $name: exit $rc, wanted a line with: $text"
    sed 's/^/    /' "$err"
    failures=$((failures + 1))
  else
    echo "ok   $name: $(head -1 "$err")"
  fi
}

# No arm on this bus: everything below is refused before the bring-up.
run_controller=("$controller" --bus loopback --episodes 5 --bootstrap 5 --quiet)

# journal.bin a symbolic link to another file: --replace must not overwrite the target.
mkdir -p "$work/link"
echo precious >"$work/link/target"
ln -s "$work/link/target" "$work/link/journal.bin"
expect journal_link "journal.bin: it is a symbolic link; refusing to follow it" \
  "${run_controller[@]}" --out "$work/link" --replace
if [[ "$(cat "$work/link/target")" != precious ]]; then
  echo "FAIL journal_link: the link's target was changed"
  failures=$((failures + 1))
fi

mkdir -p "$work/fifo" && mkfifo "$work/fifo/journal.bin"
expect journal_fifo "journal.bin: it is a FIFO, not a regular file" \
  "${run_controller[@]}" --out "$work/fifo" --replace

mkdir -p "$work/zero" && ln -s /dev/zero "$work/zero/journal.bin"
expect journal_dev_zero "journal.bin: it is a symbolic link" \
  "${run_controller[@]}" --out "$work/zero" --resume

# journal.bin a device node itself (mknod needs root; skipped without it).
mkdir -p "$work/dev"
if mknod "$work/dev/journal.bin" c 1 5 2>/dev/null; then
  expect journal_device "journal.bin: it is a character device, not a regular file" \
    "${run_controller[@]}" --out "$work/dev" --resume
fi

expect quantize_dev_zero "/dev/zero: a character device, not a regular file" \
  "$quantize" quantize --model /dev/zero --meta /dev/zero --header "$work/never.hpp"
expect evaluate_dev_zero "/dev/zero: a character device, not a regular file" \
  "$quantize" evaluate --model /dev/zero --meta /dev/zero

# The committed β-VAE with the VAE's meta JSON, in every subcommand that takes both.
models=$(cd "$(dirname "$0")/../../firmware/nn/models" && pwd)
expect quantize_other_meta "vae.meta.json is not the meta JSON of $models/beta_vae.cfm: latent" \
  "$quantize" quantize --model "$models/beta_vae.cfm" --meta "$models/vae.meta.json" \
  --header "$work/never.hpp"
expect evaluate_other_meta "vae.meta.json is not the meta JSON of $models/beta_vae.cfm: latent" \
  "$quantize" evaluate --model "$models/beta_vae.cfm" --meta "$models/vae.meta.json" \
  --test-images 10
expect check_other_meta "vae.meta.json is not the meta JSON of $models/beta_vae.cfm: latent" \
  "$quantize" check --header "$models/beta_vae_weights.hpp" --model "$models/beta_vae.cfm" \
  --meta "$models/vae.meta.json"
[[ -e "$work/never.hpp" ]] && { echo "FAIL: a header was written"; failures=$((failures + 1)); }

expect controller_noise_inf "--noise: σ must be a finite number ≥ 0 (got inf)" \
  "${run_controller[@]}" --out "$work/noise" --noise inf
if [[ -n "$lab" ]]; then
  expect lab_noise_inf "--noise: σ must be a finite number ≥ 0 (got inf)" \
    "$lab" run --algos RPE --seeds 0 --episodes 100 --noise inf --out "$work/lab" --quiet
  expect lab_window_inf "--window (W) must be a finite number ≥ 1" \
    "$lab" run --algos RPE --seeds 0 --episodes 100 --window inf --out "$work/lab" --quiet
fi

[[ $failures -eq 0 ]] && echo "all bad files refused" && exit 0
exit 1
