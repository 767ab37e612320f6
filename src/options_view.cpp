// The option table (options_table.h), part 2: camera, contours and visibility. The camera's flags need their own
// parsers (--view NAME|X,Y,Z, --size WxH, …: cli/views.cpp); the table still records and replays every field.

#include <string>
#include <vector>

#include "options_fields.h"
#include "pcsketch/neighbourhood/neighbourhoods.h"
#include "pcsketch/validate.h"

namespace pcsketch::options::detail {

namespace {

constexpr double kMaxK = neighbourhood::kMaxNeighbours;

std::vector<std::string> view_names() {
  std::vector<std::string> names;
  for (int v = 0; v <= static_cast<int>(view::NamedView::Iso); ++v)
    names.emplace_back(view::to_string(static_cast<view::NamedView>(v)));
  return names;
}

void add_camera(Builder& b) {
  b.group("Camera");
  constexpr Cli hand = Cli::HandWritten;
  b.choice(PCSKETCH_OPTION(camera.projection), {"orthographic", "perspective"},
           {.flag = "--perspective", .cli = hand, .help = "Projection (--perspective: perspective)"});
  b.add(PCSKETCH_OPTION(camera.direction),
        {.flag = "--view", .cli = hand, .help = "Direction of sight X,Y,Z (default 0,0,1: the paper looks along +z)"});
  b.choice(PCSKETCH_OPTION(camera.named), view_names(),
           {.flag = "--view", .cli = hand, .help = "A named view relative to the up vector"});
  b.add(PCSKETCH_OPTION(camera.up), {.flag = "--up", .cli = hand, .help = "Up hint X,Y,Z"});
  b.add(PCSKETCH_OPTION(camera.azimuth_deg),
        {.flag = "--azimuth",
         .cli = hand,
         .range = closed(-1e6, 1e6),
         .unit = "degrees",
         .help = "Viewer azimuth around up (0 = the front view; positive turns toward the left view)"});
  b.add(PCSKETCH_OPTION(camera.elevation_deg), {.flag = "--elevation",
                                                .cli = hand,
                                                .range = closed(-1e6, 1e6),
                                                .unit = "degrees",
                                                .help = "Viewer elevation above the horizon (positive looks down)"});
  // The camera JSON held null from 1e30 on: points stay near enough for float image coordinates.
  b.add(PCSKETCH_OPTION(camera.eye),
        {.flag = "--eye", .cli = hand, .range = closed(-1e15, 1e15), .help = "Perspective eye point X,Y,Z (world)"});
  b.add(PCSKETCH_OPTION(camera.target), {.flag = "--target",
                                         .cli = hand,
                                         .range = closed(-1e15, 1e15),
                                         .help = "Perspective target point X,Y,Z (world)"});
  b.add(PCSKETCH_OPTION(camera.fov_deg),
        {.flag = "--fov", .range = open(0, 180), .unit = "degrees", .help = "Perspective vertical field of view"});
  b.add(PCSKETCH_OPTION(camera.width), {.flag = "--size",
                                        .cli = hand,
                                        .range = closed(1, kMaxImageSide),
                                        .unit = "pixels",
                                        .help = "Image width (--size WxH)"});
  b.add(PCSKETCH_OPTION(camera.height), {.flag = "--size",
                                         .cli = hand,
                                         .range = closed(1, kMaxImageSide),
                                         .unit = "pixels",
                                         .help = "Image height (--size WxH)"});
  b.add(PCSKETCH_OPTION(camera.margin),
        {.flag = "--margin", .range = closed(0, 0.45), .help = "Empty border, fraction of the smaller image side"});
}

void add_contours(Builder& b) {
  b.group("Contours and visibility (paper IV.B)");
  b.add(PCSKETCH_OPTION(view.contours.radius_factor), {.flag = "--contour-radius",
                                                       .range = positive(1e3),
                                                       .unit = "projected spacings",
                                                       .help = "2D neighbourhood radius of the boundary test"});
  b.add(PCSKETCH_OPTION(view.contours.k), {.range = closed(1, kMaxK), .help = "Neighbours of the 2D boundary test"});
  b.add(PCSKETCH_OPTION(view.contours.gap_threshold_deg),
        {.range = above(0, 360),
         .unit = "degrees",
         .help = "A projected point with a wider angular gap is on the outline"});
  b.add(PCSKETCH_OPTION(view.contours.quadrant_test), {.help = "The paper's quadrant test instead of the gap test"});
  b.add(PCSKETCH_OPTION(view.contours.confirm_factor),
        {.range = positive(1e3), .help = "Confirmation radius of an outline point, times the test radius"});
  b.add(PCSKETCH_OPTION(view.contours.confirm_half_angle_deg),
        {.range = above(0, 180), .unit = "degrees", .help = "Half-angle of the confirmation cone"});
  b.choice(PCSKETCH_OPTION(view.contours.connection), {"direction-guided", "outermost"},
           {.flag = "--contour-connection",
            .help = "Outline tracing: outermost (no zig-zags) or direction-guided (the paper's)"});
  b.add(PCSKETCH_OPTION(view.contours.trace_radius_factor),
        {.range = positive(1e3), .unit = "projected spacings", .help = "Radius of outline tracing"});
  b.add(PCSKETCH_OPTION(view.contours.bridge_radius_factor),
        {.flag = "--bridge-radius",
         .range = non_negative(1e3),
         .unit = "projected spacings",
         .help = "Radius of the disc rolled along the outermost points to close the outline's gaps (0: off)"});
  b.add(PCSKETCH_OPTION(view.contours.z_max_factor),
        {.flag = "--z-max",
         .range = positive(1e3),
         .unit = "units of h",
         .help = "Paper's z_max: largest distance of the next contour point from the direction line"});
  b.add(PCSKETCH_OPTION(view.contours.max_turn_deg),
        {.range = above(0, 180), .unit = "degrees", .help = "Sharpest turn of an outline step"});
  b.add(PCSKETCH_OPTION(view.contours.absorb_factor), {.range = non_negative(1e3),
                                                       .unit = "projected spacings",
                                                       .help = "Outline points this near a line are absorbed"});
  b.add(PCSKETCH_OPTION(view.contours.heading_steps),
        {.range = closed(1, 1000), .help = "Steps averaged for an outline's heading"});
  b.add(PCSKETCH_OPTION(view.contours.min_length_factor),
        {.range = non_negative(), .unit = "units of h", .help = "Shorter contour lines are left out"});
  b.add(PCSKETCH_OPTION(view.contours.interior),
        {.flag = "--no-interior-contours",
         .negated = true,
         .help = "Only the outline: no occluding contours inside it (the paper's contours)"});
  b.add(PCSKETCH_OPTION(view.contours.interior_neighbours),
        {.range = closed(1, kMaxK), .help = "Neighbours compared for an n.v sign change"});
  b.add(PCSKETCH_OPTION(view.contours.interior_max_normal_angle_deg),
        {.flag = "--rim-normal-angle",
         .range = closed(0, 180),
         .unit = "degrees",
         .help = "Neighbours whose normals differ by more make no interior contour (180: off)"});
  b.add(PCSKETCH_OPTION(view.contours.interior_dedupe_factor),
        {.range = positive(1e3),
         .unit = "units of h",
         .help = "Interior contour points this near an outline are dropped"});
  b.add(PCSKETCH_OPTION(view.contours.interior_trace_radius_factor),
        {.range = positive(1e3), .unit = "units of h", .help = "Radius of interior contour tracing"});
  b.add(PCSKETCH_OPTION(view.contours.interior_z_max_factor),
        {.range = positive(1e3), .unit = "units of h", .help = "z_max of interior contour tracing"});
  b.add(PCSKETCH_OPTION(view.contours.persistence_factor),
        {.flag = "--contour-persistence",
         .range = non_negative(),
         .help = "Interior contours only where n.v reaches this many times the normals' noise on both sides (0: at "
                 "every sign change)"});
  b.add(PCSKETCH_OPTION(view.contours.denoised_min_length_factor),
        {.flag = "--denoised-contour-length",
         .range = non_negative(1e6),
         .unit = "units of h",
         .help = "On a denoised cloud, interior contours shorter than this are left out (noise squiggles)"});
  b.add(PCSKETCH_OPTION(view.contours.bend_min_f),
        {.flag = "--contour-bend",
         .range = non_negative(),
         .help = "On a denoised cloud, short interior contours are kept where n.v bends across them: the F statistic "
                 "of its plane fit reaches this (0: every short contour kept)"});
  b.add(PCSKETCH_OPTION(view.contours.denoised_min_bending),
        {.flag = "--contour-min-bending",
         .range = closed(0, 1),
         .unit = "share of samples",
         .help = "On a denoised cloud, interior contours of which fewer samples bend are left out at any length "
                 "(noise on sheets thinner than the noise; 0: off)"});
  b.add(PCSKETCH_OPTION(view.contours.depth_edge_factor),
        {.flag = "--depth-edges",
         .range = non_negative(1e6),
         .unit = "units of h",
         .help = "Interior contours where a surface ends this far in front of another (one-sided scans; 0: off)"});
  b.add(PCSKETCH_OPTION(view.contours.depth_edge_radius_factor),
        {.range = positive(1e3), .unit = "projected spacings", .help = "Image radius of the depth-edge test"});
  b.add(PCSKETCH_OPTION(view.contours.adaptive_spacing),
        {.flag = "--no-uneven-spacing",
         .negated = true,
         .help = "Outline lengths in units of the mean spacing everywhere (the paper's single radius), not of the "
                 "local spacing where the cloud is sparser"});
}

void add_visibility(Builder& b) {
  b.add(PCSKETCH_OPTION(view.visibility.self_offset_factor),
        {.flag = "--self-offset",
         .range = non_negative(1e3),
         .unit = "units of h",
         .help = "Visibility rays start this far from a line vertex (past its own and its neighbours' discs)"});
  b.add(PCSKETCH_OPTION(view.visibility.offset_from_local_spacing),
        {.flag = "--no-local-offset",
         .negated = true,
         .help = "Self offset in units of h everywhere, not of the source point's disc where the cloud is sparser"});
  b.add(PCSKETCH_OPTION(view.visibility.grazing_cos),
        {.range = closed(0, 1), .help = "Surfaces seen at a smaller |n.v| count as grazing"});
  b.add(PCSKETCH_OPTION(view.visibility.grazing_range_factor),
        {.range = non_negative(1e4), .unit = "units of h", .help = "Hits on grazing surfaces within this are ignored"});
  b.add(PCSKETCH_OPTION(view.visibility.lift_to_source_plane),
        {.flag = "--no-visibility-lift",
         .negated = true,
         .help = "Cast visibility rays from the line vertices themselves (the paper's), not lifted to the tangent "
                 "plane of their source points"});
  // Odd as well (validate.cpp): a centred window.
  b.add(PCSKETCH_OPTION(view.visibility.smoothing_window),
        {.range = closed(1, 101), .help = "Vertices of the majority filter on visibility (odd)"});
  b.add(PCSKETCH_OPTION(view.visibility.transition_refinement),
        {.range = closed(0, 30), .help = "Bisection steps locating a visibility change"});
  b.add(PCSKETCH_OPTION(scene.disc_radius_factor),
        {.range = positive(1e3), .help = "Ray-casting disc radius, times the local spacing"});
}

}  // namespace

void add_view_options(Builder& b) {
  add_camera(b);
  add_contours(b);
  add_visibility(b);
}

}  // namespace pcsketch::options::detail
