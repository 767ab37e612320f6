// The option table (options_table.h), part 3: line finish, thickness, fusion, shadows, output and plotter.

#include <nlohmann/json.hpp>

#include "options_fields.h"
#include "pcsketch/validate.h"

namespace pcsketch::options::detail {

namespace {

void add_thickness(Builder& b) {
  b.group("Stroke thickness (paper V)");
  b.choice(PCSKETCH_OPTION(thickness.model), {"constant", "depth", "angle", "combined"},
           {.flag = "--thickness",
            .help = "Width model: constant, depth (nearer thicker), angle (sharper bend thicker) or combined"});
  b.add(
      PCSKETCH_OPTION(thickness.rho_min),
      {.flag = "--rho-min", .range = non_negative(1e3), .unit = "pixels", .help = "Paper's rho_min: thinnest stroke"});
  b.add(
      PCSKETCH_OPTION(thickness.rho_max),
      {.flag = "--rho-max", .range = non_negative(1e3), .unit = "pixels", .help = "Paper's rho_max: thickest stroke"});
  b.add(PCSKETCH_OPTION(thickness.cofi),
        {.flag = "--cofi", .range = non_negative(1e3), .help = "Paper's cofi: factor on every width"});
  b.add(PCSKETCH_OPTION(thickness.normalise_cofi),
        {.help = "Segments between two vertices of width t are drawn with width t (false: the paper's raw eqs. 4-5)"});
  b.choice(PCSKETCH_OPTION(thickness.combination), {"mean", "product"},
           {.help = "Combined model: weighted mean of depth and angle widths, or their product over rho_max"});
  b.add(PCSKETCH_OPTION(thickness.angle_weight),
        {.range = closed(0, 1), .help = "Combined mean: weight of the angle width"});
  b.add(PCSKETCH_OPTION(thickness.angle_arm_px),
        {.range = positive(1e5), .unit = "pixels", .help = "Angle model: the bend is measured over this arc length"});
  b.choice(PCSKETCH_OPTION(thickness.angle_width), {"range", "paper"},
           {.help = "Angle levels over [rho_min, rho_max] (range) or as fractions of rho_max (paper)"});
  // A pair of depths, unset by default: its own JSON form {"near": …, "far": …}; validate.cpp checks both finite.
  b.custom(
      "thickness.depth_range",
      {.help = "Depth model: {near, far} depths that get rho_max and rho_min (null: the drawing's depth range)",
       .get =
           [](const DrawOptions& o) {
             const auto& r = o.thickness.depth_range;
             return r ? nlohmann::json{{"near", float_value(r->near)}, {"far", float_value(r->far)}} : nlohmann::json();
           },
       .set =
           [](DrawOptions& o, const nlohmann::json& j) {
             if (j.is_null()) return void(o.thickness.depth_range.reset());
             if (!j.is_object() || !j.contains("near") || !j.contains("far") || j.size() != 2)
               wrong("thickness.depth_range", "null or {\"near\": number, \"far\": number}", j);
             o.thickness.depth_range =
                 stylize::DepthRange{static_cast<float>(to_number("thickness.depth_range.near", j["near"])),
                                     static_cast<float>(to_number("thickness.depth_range.far", j["far"]))};
           }});
  b.add(PCSKETCH_OPTION(thickness.brush),
        {.flag = "--no-brush", .negated = true, .help = "No brush taper at the ends of lines"});
  b.add(PCSKETCH_OPTION(thickness.brush_taper_px),
        {.range = non_negative(1e5), .unit = "pixels", .help = "Brush taper length at each end of a line"});
  b.add(PCSKETCH_OPTION(thickness.brush_end_fraction),
        {.range = closed(0, 1), .help = "Brush: width at the very end, fraction of the untapered width"});
}

void add_finish(Builder& b) {
  b.group("Line finish and fusion (paper Fig. 2(d))");
  b.add(PCSKETCH_OPTION(fusion.enabled),
        {.flag = "--no-fusion",
         .negated = true,
         .help = "Draw every line as traced; by default lines running alongside each other are drawn once (contour "
                 "over ridge/valley, outline over interior contour), the other kept in the JSON as fused_into"});
  b.add(PCSKETCH_OPTION(fusion.distance_widths),
        {.flag = "--fusion-distance",
         .range = non_negative(1e3),
         .unit = "pen widths",
         .help = "Lines closer than this are one (pen width: rho-max * cofi)"});
  b.add(PCSKETCH_OPTION(fusion.min_stretch_px),
        {.flag = "--fusion-min-stretch",
         .range = non_negative(1e5),
         .unit = "pixels",
         .help = "Shortest stretch of two lines running together that is drawn once"});
  b.add(
      PCSKETCH_OPTION(fusion.max_gap_px),
      {.range = non_negative(1e5), .unit = "pixels", .help = "Gaps this short between fused stretches are fused too"});
  b.add(PCSKETCH_OPTION(fusion.max_angle_deg),
        {.range = closed(0, 90), .unit = "degrees", .help = "Lines crossing at a larger angle are not fused"});
  b.add(PCSKETCH_OPTION(finish.smooth),
        {.flag = "--no-smooth",
         .negated = true,
         .help = "Keep the traced vertices; by default lines are smoothed, corners kept"});
  b.add(PCSKETCH_OPTION(finish.smooth_passes), {.range = closed(0, 100), .help = "Taubin smoothing passes"});
  b.add(PCSKETCH_OPTION(finish.corner_angle_deg),
        {.range = closed(0, 180), .unit = "degrees", .help = "Vertices bent sharper than this are corners: not moved"});
  b.add(PCSKETCH_OPTION(finish.corner_arm_px),
        {.range = non_negative(1e5), .unit = "pixels", .help = "Arm of the corner test"});
  b.add(PCSKETCH_OPTION(finish.min_length_px),
        {.flag = "--min-stroke-length",
         .range = non_negative(1e5),
         .unit = "pixels",
         .help = "Lines seen over less than this are left out (a stub continuing a longer line stays)"});
  b.add(PCSKETCH_OPTION(finish.join_px),
        {.range = non_negative(1e5), .unit = "pixels", .help = "A short line ending this near a longer one stays"});
}

void add_light(Builder& b) {
  b.group("Shadows (paper VI)");
  b.choice(PCSKETCH_OPTION(shadow.mode), {"none", "paper", "attached", "both"},
           {.flag = "--shadow",
            .help = "none, paper (hatching between ridge/valley lines and their projection along the light), attached "
                    "(hatching of the surface facing away from the light) or both"});
  // Direction non-zero: validate.cpp.
  b.add(PCSKETCH_OPTION(shadow.light.direction),
        {.flag = "--light",
         .help = "Light travel direction X,Y,Z (default: 45 degrees to xoy, parallel to xoz, Fig. 13; see "
                 "--light-fixed)"});
  // Embree aborts on rays with NaN directions: a light angle must be finite.
  b.add(PCSKETCH_OPTION(shadow.light.elevation_deg), {.flag = "--light-elevation",
                                                      .range = closed(-1e6, 1e6),
                                                      .unit = "degrees",
                                                      .help = "Light angle to the xoy plane"});
  b.add(PCSKETCH_OPTION(shadow.light.azimuth_deg), {.flag = "--light-azimuth",
                                                    .range = closed(-1e6, 1e6),
                                                    .unit = "degrees",
                                                    .help = "Light rotation around z (0: xoz plane)"});
  b.add(PCSKETCH_OPTION(shadow.light.follow_camera),
        {.flag = "--light-fixed",
         .negated = true,
         .help = "Light direction in world axes; by default it is read in the camera's frame and turns with the view "
                 "(the same for the paper's +z view)"});
}

void add_paper_shadow(Builder& b) {
  b.add(PCSKETCH_OPTION(shadow.k_set), {.flag = "--shadow-k",
                                        .range = positive(1e3),
                                        .help = "Paper's k set (eq. 14), e.g. --shadow-k 0.0625 0.125 0.25 0.5"});
  b.add(PCSKETCH_OPTION(shadow.d), {.flag = "--shadow-d",
                                    .range = positive(1e4),
                                    .help = "Paper's d (eq. 14): hatch lines at t = k*d along the shadow"});
  b.add(PCSKETCH_OPTION(shadow.cast_from_valleys), {.help = "Valley lines cast shadows too"});
  b.add(PCSKETCH_OPTION(shadow.ray_offset_factor),
        {.range = non_negative(1e4), .unit = "units of h", .help = "Light rays start this far from the line vertex"});
  b.add(PCSKETCH_OPTION(shadow.max_cast_factor),
        {.range = positive(1e6),
         .unit = "units of h",
         .help = "A vertex whose light ray hits nothing within this casts none"});
  b.add(PCSKETCH_OPTION(shadow.visibility_offset_factor),
        {.range = non_negative(1e4),
         .unit = "units of h",
         .help = "Hatch points are tested toward the camera from this offset"});
  b.add(PCSKETCH_OPTION(shadow.clip_to_surface),
        {.flag = "--shadow-over-background",
         .negated = true,
         .help = "Paper mode: draw the whole region between a line and its projection, also where the background "
                 "is seen through it; shading is not cut to the silhouette (default: only over the surface)"});
  b.add(PCSKETCH_OPTION(shadow.max_jump_factor),
        {.range = positive(1e6), .help = "Hatch strokes break where projections jump farther than this many spacings"});
  b.add(PCSKETCH_OPTION(shadow.cast_hatch_width_px),
        {.range = non_negative(1e3), .unit = "pixels", .help = "Width of the paper's hatch strokes"});
  b.add(PCSKETCH_OPTION(shadow.cast_grey_near),
        {.range = closed(0, 1), .help = "Grey of the hatch line nearest the line"});
  b.add(PCSKETCH_OPTION(shadow.cast_grey_far), {.range = closed(0, 1), .help = "Grey of the farthest hatch line"});
  b.add(PCSKETCH_OPTION(shadow.shade_blocks),
        {.flag = "--no-shade-blocks", .negated = true, .help = "Paper mode: no grey blocks, hatch strokes only"});
  b.add(PCSKETCH_OPTION(shadow.block_grey_near),
        {.range = closed(0, 1), .help = "Grey of the block touching the line"});
  b.add(PCSKETCH_OPTION(shadow.block_grey_far), {.range = closed(0, 1), .help = "Grey of the outermost block"});
}

void add_attached_shadow(Builder& b) {
  b.add(PCSKETCH_OPTION(shadow.attached_levels),
        {.range = closed(-1, 1), .help = "n.l thresholds of the attached hatch families"});
  // Each hatch line is a path in the output: spacing bounds the output size (0.001 px made a 129 MB SVG).
  b.add(PCSKETCH_OPTION(shadow.hatch_spacing_px), {.flag = "--hatch-spacing",
                                                   .range = closed(kMinHatchSpacingPx, 1e5),
                                                   .unit = "pixels",
                                                   .help = "Attached hatching: distance between lines"});
  b.add(PCSKETCH_OPTION(shadow.hatch_angle_deg),
        {.range = closed(-360, 360), .unit = "degrees", .help = "Angle of the first hatch family"});
  b.add(PCSKETCH_OPTION(shadow.cross_angle_deg),
        {.range = closed(-360, 360), .unit = "degrees", .help = "Each further family turns by this much"});
  b.add(PCSKETCH_OPTION(shadow.attached_width_px),
        {.range = non_negative(1e3), .unit = "pixels", .help = "Attached hatch stroke width"});
  b.add(PCSKETCH_OPTION(shadow.attached_grey_light), {.range = closed(0, 1), .help = "Grey of the first family"});
  b.add(PCSKETCH_OPTION(shadow.attached_grey_dark), {.range = closed(0, 1), .help = "Grey of the last family"});
  b.add(PCSKETCH_OPTION(shadow.mask_cell_px),
        {.range = closed(0.5, 1e4), .unit = "pixels", .help = "Cell size of the image-space shading grid"});
  b.add(PCSKETCH_OPTION(shadow.splat_radius_factor),
        {.range = positive(1e3), .help = "Splatted disc radius, times the local spacing"});
  b.add(PCSKETCH_OPTION(shadow.depth_jump_factor), {.range = positive(1e6),
                                                    .unit = "units of h",
                                                    .help = "Hatch lines break where the visible depth jumps by more"});
  b.add(PCSKETCH_OPTION(shadow.attached_min_facing),
        {.range = closed(0, 1), .help = "Cells facing the viewer less than this (-n.v) are not hatched"});
  b.add(PCSKETCH_OPTION(shadow.min_hatch_px),
        {.range = non_negative(1e6), .unit = "pixels", .help = "Shorter hatch pieces are dropped"});
}

void add_output(Builder& b) {
  b.group("Output");
  b.add(PCSKETCH_OPTION(lines.contours), {.flag = "--no-contours", .negated = true, .help = "Leave out contours"});
  b.add(PCSKETCH_OPTION(lines.ridges), {.flag = "--no-ridges", .negated = true, .help = "Leave out ridge lines"});
  b.add(PCSKETCH_OPTION(lines.valleys), {.flag = "--no-valleys", .negated = true, .help = "Leave out valley lines"});
  b.add(PCSKETCH_OPTION(lines.hatching),
        {.flag = "--no-hatching", .negated = true, .help = "Leave out shadow hatching and shading"});
  b.add(PCSKETCH_OPTION(lines.boundaries),
        {.flag = "--no-boundaries",
         .negated = true,
         .help = "Leave out the border lines of open scans (the outline does not run along them either)"});
  b.choice(PCSKETCH_OPTION(render.hidden_lines), {"none", "dashed"},
           {.flag = "--hidden-lines", .help = "Hidden lines: none, or dashed (thin grey, in their own SVG layer)"});
  b.add(PCSKETCH_OPTION(render.plotter),
        {.flag = "--plotter",
         .help = "Pen-plotter output: centre-lines of one width, no grey fills; strokes merged where their ends meet, "
                 "collinear hatching drawn once, dabs left out, each layer sorted to shorten pen-up travel"});
  b.add(PCSKETCH_OPTION(render.pen_width_mm), {.flag = "--pen-width-mm",
                                               .alias = "--pen-width",
                                               .range = positive(100),
                                               .unit = "page mm",
                                               .help = "Plotter line width"});
  b.add(PCSKETCH_OPTION(render.pen_width),
        {.flag = "--pen-width-px",
         .range = positive(1e3),
         .unit = "pixels",
         .help = "Plotter line width in image pixels (what --pen-width meant before it took millimetres)"});
  b.add(PCSKETCH_OPTION(render.default_width),
        {.range = positive(1e3), .unit = "pixels", .help = "Width of strokes that carry no widths"});
  b.add(PCSKETCH_OPTION(render.width_step),
        {.range = non_negative(1e3), .unit = "pixels", .help = "Stroke widths are rounded to this step"});
  b.add(PCSKETCH_OPTION(render.hidden_width), {.range = positive(1e3), .unit = "pixels", .help = "Hidden line width"});
  b.add(PCSKETCH_OPTION(render.hidden_grey), {.range = closed(0, 1), .help = "Hidden line grey"});
  b.add(PCSKETCH_OPTION(render.hidden_dash),
        {.range = positive(1e5), .unit = "pixels", .help = "Hidden line dash (and gap) length"});
  b.add(PCSKETCH_OPTION(render.shading), {.help = "Draw the grey shade blocks (never in plotter mode)"});
  b.add(PCSKETCH_OPTION(render.page_width_mm), {.flag = "--page-width-mm",
                                                .range = positive(1e5),
                                                .unit = "mm",
                                                .help = "SVG/PDF page width (default: the image size in CSS pixels)"});
  b.add(PCSKETCH_OPTION(render.decimals), {.range = closed(0, 6), .help = "Decimals of SVG coordinates"});
}

void add_plotter(Builder& b) {
  b.add(PCSKETCH_OPTION(plotter.merge_tolerance_mm),
        {.flag = "--merge-tolerance-mm",
         .range = non_negative(100),
         .unit = "page mm",
         .help = "Plotter: join strokes whose ends are this close (0: only ends that coincide)"});
  b.add(PCSKETCH_OPTION(plotter.collinear_tolerance_mm),
        {.range = non_negative(100), .unit = "page mm", .help = "Plotter: collinear hatch pieces within this are one"});
  b.add(PCSKETCH_OPTION(plotter.min_stroke_mm),
        {.flag = "--min-stroke-mm",
         .range = non_negative(1e4),
         .unit = "page mm",
         .help = "Plotter: leave out strokes shorter than this after merging (0 keeps all)"});
  b.add(PCSKETCH_OPTION(plotter.merge), {.help = "Plotter: join strokes whose ends meet"});
  b.add(PCSKETCH_OPTION(plotter.sort), {.flag = "--no-plot-sort",
                                        .negated = true,
                                        .help = "Plotter: keep the drawing order of strokes (no pen-travel sort)"});
}

void add_page(Builder& b) {
  b.group("Page and scale");
  // Bound by hand: the CLI reads "1:20" (cli/page_options.cpp); JSON holds the ratio itself.
  b.add(PCSKETCH_OPTION(page.scale),
        {.flag = "--scale",
         .cli = Cli::HandWritten,
         .range = {0, 1e6, true},
         .unit = "page / model",
         .help = "Draw at this scale, page : model, e.g. 1:20 (needs --units; orthographic views): the SVG/PDF page "
                 "is sized from the model instead of --page-width-mm"});
  b.choice(PCSKETCH_OPTION(page.units), {"none", "mm", "cm", "m"},
           {.flag = "--units", .help = "Unit of the model's coordinates, for --scale and the scale bar's figures"});
  b.add(PCSKETCH_OPTION(page.scale_bar),
        {.flag = "--scale-bar",
         .help = "A scale bar (a round length in model units) and the stated scale, in a band under the drawing, "
                 "layer '8 annotations'"});
  b.add(PCSKETCH_OPTION(page.north_arrow),
        {.flag = "--north-arrow",
         .help = "An arrow along the model's +y axis (north for georeferenced scans) beside the scale bar"});
}

void add_limits(Builder& b) {
  b.group("Input");
  b.add(PCSKETCH_OPTION(min_points),
        {.range = closed(0, 1e12), .help = "Clouds with fewer points give an empty drawing and a warning"});
  // Bound by hand: `features` sets its own copy (cli/options.cpp add_memory_option).
  b.add(PCSKETCH_OPTION(max_memory_gb),
        {.flag = "--max-memory",
         .cli = Cli::HandWritten,
         .range = positive(1e6),
         .unit = "GB",
         .help = "Refuse a cloud estimated to need more memory than this, before the analysis starts (default: the "
                 "machine's memory)"});
}

}  // namespace

void add_drawing_options(Builder& b) {
  add_thickness(b);
  add_finish(b);
  add_light(b);
  add_paper_shadow(b);
  add_attached_shadow(b);
  add_output(b);
  add_plotter(b);
  add_page(b);
  add_limits(b);
}

}  // namespace pcsketch::options::detail
