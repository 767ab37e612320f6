#include "pcsketch/render/write.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cctype>
#include <exception>
#include <memory>

#include "pcsketch/core/atomic_file.h"
#include "pcsketch/core/error.h"
#include "pcsketch/render/json.h"
#include "pcsketch/render/pdf.h"
#include "pcsketch/render/png.h"
#include "pcsketch/render/svg.h"

namespace pcsketch::render {

namespace {

std::string extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// `drawing` written in full to a temporary file next to `path`, which is removed unless committed.
std::unique_ptr<TempFile> write_temporary(const Drawing& drawing, const std::filesystem::path& path,
                                          const RenderOptions& options) {
  const std::string ext = extension(path);
  if (!is_supported_output(path))
    throw Error(path.string() + ": output: unknown format (use .svg, .pdf, .png or .json)");
  auto file = std::make_unique<TempFile>(path);
  try {
    if (ext == ".svg")
      write_svg(drawing, file->path(), options);
    else if (ext == ".pdf")
      write_pdf(drawing, file->path(), options);
    else if (ext == ".png")
      write_png(drawing, file->path(), options);
    else
      write_json(drawing, file->path());
  } catch (const Error& e) {
    // The writers name the file they wrote: the temporary one, which the user never asked for.
    const std::string message = e.what(), temp = file->path().string();
    throw Error(path.string() + (message.starts_with(temp) ? message.substr(temp.size()) : ": " + message));
  }
  return file;
}

}  // namespace

void write_drawing(const Drawing& drawing, const std::filesystem::path& path, const RenderOptions& options) {
  write_temporary(drawing, path, options)->commit();
}

bool is_supported_output(const std::filesystem::path& path) {
  const std::string ext = extension(path);
  return ext == ".svg" || ext == ".pdf" || ext == ".png" || ext == ".json";
}

void check_output(const std::filesystem::path& path) {
  if (!is_supported_output(path))
    throw Error(FileLoc{path.string(), {}, {}}, "unknown output format (use .svg, .pdf, .png or .json)");
  check_writable(path);
}

void write_drawings(const Drawing& drawing, const std::vector<std::filesystem::path>& paths,
                    const RenderOptions& options, const ProgressFn& progress) {
  const ProgressReporter report(progress, "writing");
  report(0.0);
  // Failures are caught per file: an exception escaping a TBB task would cancel the writes not yet started.
  std::vector<std::unique_ptr<TempFile>> files(paths.size());
  std::vector<std::exception_ptr> errors(paths.size());
  tbb::parallel_for(std::size_t{0}, paths.size(), [&](std::size_t i) {
    try {
      files[i] = write_temporary(drawing, paths[i], options);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  // Every file is complete but none renamed yet: a stop asked for here leaves no output (`files` removes them).
  report(1.0);
  for (std::size_t i = 0; i < paths.size(); ++i) {
    try {
      if (files[i]) files[i]->commit();
    } catch (...) {
      errors[i] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace pcsketch::render
