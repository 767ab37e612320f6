#include "render/grey_png.h"

#include <zlib.h>

#include <array>
#include <fstream>
#include <string>
#include <vector>

#include "pcsketch/core/error.h"

namespace pcsketch::render::detail {

namespace {

void append_u32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>(v >> shift & 0xffu));
}

/// Length, type, data and CRC of one PNG chunk.
void write_chunk(std::ofstream& file, const char (&type)[5], const std::uint8_t* data, std::size_t size) {
  std::string head;
  append_u32(head, static_cast<std::uint32_t>(size));
  head.append(type, 4);
  uLong crc = crc32(0, reinterpret_cast<const Bytef*>(type), 4);
  if (size > 0) crc = crc32(crc, data, static_cast<uInt>(size));
  std::string tail;
  append_u32(tail, static_cast<std::uint32_t>(crc));
  file.write(head.data(), static_cast<std::streamsize>(head.size()));
  file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  file.write(tail.data(), static_cast<std::streamsize>(tail.size()));
}

/// deflate's state, released however the encoder leaves.
struct Deflater {
  z_stream stream{};
  bool open = false;
  ~Deflater() {
    if (open) deflateEnd(&stream);
  }
};

}  // namespace

void write_grey_png(const std::uint8_t* pixels, int width, int height, std::ptrdiff_t stride,
                    const std::filesystem::path& path) {
  const auto fail = [&](const std::string& why) { return Error(path.string() + ": PNG: " + why); };
  std::ofstream file(path, std::ios::binary);
  if (!file) throw fail("cannot open the file for writing");
  static constexpr std::array<std::uint8_t, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  file.write(reinterpret_cast<const char*>(kSignature.data()), kSignature.size());
  std::string header;
  append_u32(header, static_cast<std::uint32_t>(width));
  append_u32(header, static_cast<std::uint32_t>(height));
  header += std::string{8, 0, 0, 0, 0};  // bit depth 8, greyscale, deflate, filter method 0, no interlace
  write_chunk(file, "IHDR", reinterpret_cast<const std::uint8_t*>(header.data()), header.size());
  const std::array<std::uint8_t, 2> background = {0, 0xff};  // white, as cairo records it
  write_chunk(file, "bKGD", background.data(), background.size());

  Deflater z;
  if (deflateInit(&z.stream, Z_BEST_SPEED) != Z_OK) throw fail("zlib cannot start");
  z.open = true;
  // Rows stream through: each one is a filter byte (0, none) and its pixels; full output buffers become IDAT chunks.
  std::vector<std::uint8_t> row(static_cast<std::size_t>(width) + 1, 0);
  std::vector<std::uint8_t> out(1 << 16);
  const auto pump = [&](int flush) {
    int status;
    do {
      z.stream.next_out = out.data();
      z.stream.avail_out = static_cast<uInt>(out.size());
      status = deflate(&z.stream, flush);
      if (status == Z_STREAM_ERROR) throw fail("zlib failed");
      const std::size_t produced = out.size() - z.stream.avail_out;
      if (produced > 0) write_chunk(file, "IDAT", out.data(), produced);
    } while (z.stream.avail_out == 0 || (flush == Z_FINISH && status != Z_STREAM_END));
  };
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* src = pixels + static_cast<std::ptrdiff_t>(y) * stride;
    std::copy(src, src + width, row.begin() + 1);
    z.stream.next_in = row.data();
    z.stream.avail_in = static_cast<uInt>(row.size());
    pump(Z_NO_FLUSH);
  }
  pump(Z_FINISH);
  write_chunk(file, "IEND", nullptr, 0);
  if (!file.flush()) throw fail("cannot write the file");
}

}  // namespace pcsketch::render::detail
