#pragma once
// Reading point clouds and meshes: one entry point, one dispatch table choosing the reader by the file's first bytes
// (magic "ply", "OFF", a PCD header) and then by its extension (docs/io.md lists the formats).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pcsketch/core/point_cloud.h"
#include "pcsketch/core/report.h"
#include "pcsketch/io/decimate.h"

namespace pcsketch::io {

/// What one column of a text file (XYZ/PTS/TXT/CSV/ASC) holds.
enum class Column : std::uint8_t { X, Y, Z, Nx, Ny, Nz, Red, Green, Blue, Intensity, Skip };

/// Parses a column list such as "x,y,z,r,g,b" (names: x y z r g b i nx ny nz skip; case-insensitive; the long
/// forms red green blue intensity too).
/// @throws pcsketch::Error naming the unknown or repeated name, or when x, y or z is missing.
std::vector<Column> parse_columns(std::string_view spec);

/// An axis-aligned box in the file's own coordinates (before recentring).
struct CropBox {
  Vec3d min;
  Vec3d max;
};

struct ReadOptions {
  /// Recentre the cloud on a double origin (the bounding-box centre rounded to whole units) when it lies far from
  /// the world origin (further than 8 bounding-box extents): float positions then keep sub-millimetre precision on
  /// georeferenced scans with 6-digit UTM offsets. Off: origin = 0 and positions are the world coordinates as float.
  bool recentre = true;
  /// Keep the per-point normals of the file (nx ny nz). Off: the cloud has no normals, as a raw scan.
  bool keep_normals = true;
  /// Keep the per-point colours of the file (red green blue).
  bool keep_colors = true;
  /// Text files: what each column holds. Empty: a header row names the columns, else they are guessed from the
  /// values (columns 4-6 are normals only if they are unit vectors; docs/io.md).
  std::vector<Column> columns;
  /// Keep only the points whose classification (LAS) is one of these; empty: every class.
  std::vector<int> classes;
  /// Remove the points whose classification (LAS) is one of these (7 = noise); applied after `classes`.
  std::vector<int> drop_classes;
  /// Keep only the points inside this box (bounds included), in file coordinates; none: every point.
  std::optional<CropBox> crop;
  /// Voxel thinning after cropping (off by default: every point is kept).
  DecimateOptions decimate;
  /// Keep only the first of points with exactly equal coordinates (one warning counts the others): m copies of a
  /// point would make every neighbourhood query around it cost m, and they add nothing to the surface.
  bool collapse_duplicates = true;
  /// Points per chunk of a streamed read (PLY, LAS, ascii and binary PCD, the XYZ family; thinned while read,
  /// docs/io.md); the kept points do not depend on it (tests read with tiny chunks).
  std::size_t stream_chunk_points = 1 << 16;
  /// Optional: "read" from 0 at the start to 1 when the cloud is ready (text files also as their lines are parsed);
  /// returning false stops the read (pcsketch::Cancelled).
  ProgressFn progress;
};

/// A cloud as read, plus what the reader noticed.
struct ReadResult {
  PointCloud cloud;                           ///< #P finite points; source_index empty (file order)
  std::string format;                         ///< reader and layout, e.g. "ply binary_little_endian", "xyz", "off"
  std::string columns;                        ///< text formats: "x,y,z,r,g,b (guessed from the values)"
  Warnings warnings;                          ///< one line each, e.g. the count of dropped non-finite points
  std::size_t dropped_non_finite = 0;         ///< points with a NaN or infinite coordinate, not in `cloud`
  std::size_t duplicates = 0;                 ///< exact copies of earlier points, not in `cloud`
  std::size_t points_in_file = 0;             ///< points the file holds, dropped ones included
  std::size_t dropped_by_filter = 0;          ///< points outside the crop box or of an unwanted class
  std::optional<DecimateReport> decimation;   ///< set when ReadOptions::decimate asked for thinning
  std::vector<std::string> other_attributes;  ///< per-point properties/columns present in the file but not kept
};

/// Reads the points of a PLY, LAS, XYZ/PTS/TXT/CSV/ASC, PCD, OFF or OBJ file (the vertices of a mesh are its points).
/// The file is mapped into memory once; header counts are checked against the file size before anything is
/// allocated. Points with a NaN or infinite coordinate are dropped with one warning counting them; then the
/// class filters and the crop box apply, then the thinning.
/// @throws pcsketch::Error naming the file and the line (text) or byte offset (binary) for an empty, truncated,
///         malformed or unknown file, and when no finite point is left.
ReadResult read_point_cloud(const std::string& path, const ReadOptions& options = {});

/// As read_point_cloud, from bytes already in memory (fuzzing, tests). `name_hint` stands for the path: its
/// extension helps choose the reader and it names the input in error messages.
ReadResult read_point_cloud_from_memory(std::string_view bytes, const std::string& name_hint,
                                        const ReadOptions& options = {});

/// The number of points a file's header declares (PLY, LAS, PCD), checked against the file size; nullopt
/// for the other formats, whose count is known only once read. @throws pcsketch::Error for a malformed header.
std::optional<std::uint64_t> points_in_header(const std::string& path);

/// The up axis a file's format fixes: +z for LAS (the ASPRS format's z is elevation), nullopt for the others, whose
/// axes follow no convention. Reads the file's first bytes only; nullopt for a file it cannot read (the read itself
/// then gives the error).
std::optional<Vec3d> conventional_up(const std::string& path);

/// The rows of a text cloud (the XYZ family), which declares no count, estimated from the lengths of the lines at 256
/// evenly spaced offsets (within a few percent of its data rows); nullopt for other formats and one-line texts.
/// @throws pcsketch::Error for an empty or unreadable file.
std::optional<std::uint64_t> estimated_text_rows(const std::string& path);

/// Largest and smallest bounding-box side a cloud may have to be drawn. Positions are float and squared distances
/// must stay far inside float range: a cloud in 1e30 or 1e-30 units (or one stray point at 1e30) is refused with a
/// message saying so rather than analysed into a zero spacing or a null camera.
inline constexpr double kMaxCloudExtent = 1e12;
inline constexpr double kMinCloudExtent = 1e-9;

/// Checks that `cloud` spans between kMinCloudExtent and kMaxCloudExtent units (a single point, extent 0, passes).
/// @throws pcsketch::Error naming `name` and the extent otherwise.
void check_scale(const PointCloud& cloud, const std::string& name);

/// Reads a triangle mesh from PLY (element "face", list property vertex_indices/vertex_index), OFF or OBJ.
/// Polygons are triangulated as fans around their first vertex; faces with fewer than 3 vertices are ignored.
/// Vertices are recentred as in read_point_cloud.
/// @throws pcsketch::Error for a malformed file, a face index out of range, a non-finite vertex, or no faces.
Mesh read_mesh(const std::string& path, const ReadOptions& options = {});

/// As read_mesh, from bytes in memory; `name_hint` as in read_point_cloud_from_memory.
Mesh read_mesh_from_memory(std::string_view bytes, const std::string& name_hint, const ReadOptions& options = {});

}  // namespace pcsketch::io
