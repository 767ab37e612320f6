// Must not compile: differential reaching into render's private header (tests/CMakeLists.txt, test
// build.stage_walls). A stage sees its own folder, core's shared helpers (src/internal/core/) and public headers only.

#include "core/parallel_chunks.h"  // shared by every stage: found
#include "render/paint.h"          // another stage's private header: not found
