#pragma once
// Invariant checks that stay on in release builds (geometry-central's GC_SAFETY_ASSERT).

#include <string>

#include "pcsketch/core/error.h"

namespace pcsketch::detail {
[[noreturn]] void assert_failed(const char* condition, const char* file, int line, const std::string& message);
}  // namespace pcsketch::detail

/// Always-on check: throws pcsketch::Error with file:line when cond is false.
#define PCS_ASSERT(cond, msg)                                                       \
  do {                                                                              \
    if (!(cond)) ::pcsketch::detail::assert_failed(#cond, __FILE__, __LINE__, msg); \
  } while (0)

/// Debug-only check for hot loops.
#ifdef NDEBUG
#define PCS_DASSERT(cond, msg) \
  do {                         \
  } while (0)
#else
#define PCS_DASSERT(cond, msg) PCS_ASSERT(cond, msg)
#endif
