#include "pcsketch/core/report.h"

namespace pcsketch {

void ProgressReporter::operator()(double fraction) const {
  if (fn_ && !fn_(stage_, fraction)) throw Cancelled();
}

}  // namespace pcsketch
