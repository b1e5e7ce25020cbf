// The project's one progress and cancellation convention.
//
// A long kernel takes a ProgressReport in its options and calls it through
// reportProgress with the fraction done (0..1, never decreasing) and the name of
// the stage it is in. A report only informs: it cannot stop the kernel. Stopping
// belongs to the caller's CancellationScope (Cancellation.h), which
// reportProgress checks after every report and the kernels' long loops poll, so
// ParaView's abort or Ctrl-C ends a kernel at its next report or poll with
// tsynth::Cancelled, whoever asked for the progress.
#pragma once

#include "Core/Cancellation.h"

#include <functional>
#include <string>

namespace tsynth
{

using ProgressReport = std::function<void(double fraction, const std::string& stage)>;

// Reports (if anyone listens), then throws tsynth::Cancelled if the open scope
// says stop. Call it on the thread that opened the scope, outside parallel regions.
inline void reportProgress(const ProgressReport& report, double fraction, const std::string& stage)
{
  if (report)
  {
    report(fraction, stage);
  }
  checkCancellation();
}

} // namespace tsynth
