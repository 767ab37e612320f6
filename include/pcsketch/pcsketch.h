#pragma once
// Umbrella header: the whole library. Most programs need only prepare()/draw_view() (pipeline.h), a reader
// (io/read_cloud.h) and a writer (render/write.h).

#include "pcsketch/core/allocator.h"
#include "pcsketch/core/drawing.h"
#include "pcsketch/core/error.h"
#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/polyline.h"
#include "pcsketch/core/report.h"
#include "pcsketch/differential/surface.h"
#include "pcsketch/features/ridge_valley_lines.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/io/sample_mesh.h"
#include "pcsketch/pipeline.h"
#include "pcsketch/render/json.h"
#include "pcsketch/render/pdf.h"
#include "pcsketch/render/png.h"
#include "pcsketch/render/svg.h"
#include "pcsketch/render/write.h"
#include "pcsketch/stylize/thickness.h"
#include "pcsketch/validate.h"
#include "pcsketch/view/camera.h"
#include "pcsketch/view/view.h"
