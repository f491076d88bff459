// The end of a controller image's run report, printed alike by the images that talk to a real
// link (the Cortex-M7 SLCAN image, tests/app/qemu_slcan/; the ZynqMP CAN image, tests/zynqmp/):
// the faults by kind, the encoder's calls, the archive's FNV-1a checksum (which the test
// scripts compare with `curio-controller --print-checksum`) and PASS or FAILED. Each image
// prints through its own console (semihosting, a UART), given as an ImagePrinter.
// Freestanding: no heap.
#pragma once
#include <cstddef>
#include <cstdint>

#include "firmware/app/controller.hpp"
#include "firmware/explore/explorer.hpp"
#include "firmware/explore/fnv1a.hpp"
#include "firmware/nn/encoder.hpp"

namespace curio::test {

struct ImagePrinter {
  void (*text)(const char*);
  void (*u32)(uint64_t);
  void (*hex32)(uint32_t);
};

// "\n    <fault> <count>" for every fault kind that occurred.
inline void print_fault_kinds(const ImagePrinter& out, const app::ControllerCounters& c) {
  for (size_t k = 0; k < app::kFaultKinds; ++k) {
    if (c.faults[k] == 0) continue;
    out.text("\n    ");
    out.text(app::to_string(static_cast<app::Fault>(k)));
    out.text(" ");
    out.u32(c.faults[k]);
  }
}

// From the fault total on: "<total> (last <fault>), replays ..., capture retries ...,
// unexpected/malformed/foreign a/b/c", the faults by kind, the encoder's calls (encoder
// non-null), the archive checksum, then PASS or FAILED. Returns the image's exit code.
inline int print_run_end(const ImagePrinter& out, const app::ControllerCounters& c,
                         const nn::Encoder* encoder, const Explorer& explorer, bool ok) {
  out.u32(c.fault_total);
  out.text(" (last ");
  out.text(app::to_string(c.last_fault));
  out.text("), replays ");
  out.u32(c.replays);
  out.text(", capture retries ");
  out.u32(c.capture_retries);
  out.text(", unexpected/malformed/foreign ");
  out.u32(c.unexpected_frames);
  out.text("/");
  out.u32(c.malformed_frames);
  out.text("/");
  out.u32(c.foreign_frames);
  print_fault_kinds(out, c);
  if (encoder != nullptr) {
    out.text(", encoder calls ");
    out.u32(encoder->encodes());
    out.text(" (faults ");
    out.u32(encoder->faults());
    out.text(")");
  }
  Fnv1a archive;
  archive.add_archive(explorer.archive());
  out.text("\narchive checksum ");
  out.hex32(archive.h);
  out.text(" (");
  out.u32(static_cast<uint32_t>(explorer.archive().size()));
  out.text(" episodes)\n");
  out.text(ok ? "PASS\n" : "FAILED\n");
  return ok ? 0 : 1;
}

}  // namespace curio::test
