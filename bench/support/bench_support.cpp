#include "support/bench_support.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

#include "pcsketch/core/allocator.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/io/sample_mesh.h"

namespace pcsketch::bench {

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

std::size_t peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::size_t>(usage.ru_maxrss) * 1024;  // kilobytes on Linux
}

std::size_t current_rss_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  if (!(in >> one >> five >> fifteen)) return "unknown";
  return one + " " + five + " " + fifteen;
}

std::string run_isolated(const std::function<std::string()>& job) {
  int channel[2];
  if (pipe(channel) != 0) throw std::runtime_error("bench: pipe failed");
  const pid_t child = fork();
  if (child < 0) throw std::runtime_error("bench: fork failed");
  if (child == 0) {
    close(channel[0]);
    int status = 0;
    try {
      const std::string out = job();
      for (std::size_t done = 0; done < out.size();) {
        const ssize_t w = write(channel[1], out.data() + done, out.size() - done);
        if (w <= 0) break;
        done += static_cast<std::size_t>(w);
      }
    } catch (const std::exception& e) {
      const std::string message = std::string("error: ") + e.what();
      (void)!write(channel[1], message.data(), message.size());
      status = 1;
    }
    close(channel[1]);
    _exit(status);
  }
  close(channel[1]);
  std::string out;
  char buffer[4096];
  for (ssize_t r; (r = read(channel[0], buffer, sizeof buffer)) > 0;) out.append(buffer, static_cast<std::size_t>(r));
  close(channel[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("bench: child process failed" + (out.empty() ? std::string() : ": " + out));
  return out;
}

std::string Table::to_string() const {
  // Columns are counted in UTF-8 code points ("µs", "—"), not bytes: continuation bytes 10xxxxxx take no column.
  const auto columns = [](const std::string& text) {
    return static_cast<std::size_t>(
        std::count_if(text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
  };
  std::vector<std::size_t> width(header_.size(), 0);
  const auto measure = [&](const std::vector<std::string>& row) {
    for (std::size_t c = 0; c < row.size() && c < width.size(); ++c) width[c] = std::max(width[c], columns(row[c]));
  };
  measure(header_);
  for (const auto& row : rows_) measure(row);
  std::ostringstream out;
  const auto line = [&](const std::vector<std::string>& row) {
    for (std::size_t c = 0; c < width.size(); ++c) {
      const std::string cell = c < row.size() ? row[c] : "";
      const std::string pad(width[c] - columns(cell), ' ');
      out << (c ? "  " : "") << (c == 0 ? cell + pad : pad + cell);
    }
    out << '\n';
  };
  line(header_);
  out << std::string(std::accumulate(width.begin(), width.end(), 2 * (width.size() - 1)), '-') << '\n';
  for (const auto& row : rows_) line(row);
  return out.str();
}

std::string fixed(double value, int digits) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(digits);
  out << value;
  return out.str();
}

std::string grouped(std::size_t count) {
  std::string digits = std::to_string(count);
  for (std::ptrdiff_t at = static_cast<std::ptrdiff_t>(digits.size()) - 3; at > 0; at -= 3) digits.insert(at, ",");
  return digits;
}

std::string mebibytes(std::size_t bytes) { return fixed(static_cast<double>(bytes) / (1024.0 * 1024.0), 1) + " MiB"; }

std::string shared_data(const std::string& name) { return std::string(PCSKETCH_SHARED_DATA) + "/" + name; }

void shuffle(PointCloud& cloud, std::uint64_t seed) {
  std::vector<std::uint32_t> order(cloud.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937_64(seed));
  permute(cloud, order);
}

PointCloud sampled_cloud(const std::string& path, std::size_t n, std::uint64_t seed) {
  const Mesh mesh = io::read_mesh(path);
  PointCloud cloud = io::sample_mesh(mesh, {.n = n, .seed = seed});
  cloud.normals.clear();
  shuffle(cloud, seed);
  cloud.source_index.clear();
  return cloud;
}

Table per_point_table(const std::string& first, const std::vector<std::string>& names) {
  std::vector<std::string> header{first};
  for (const std::string& name : names) {
    header.push_back(name + " s");
    header.push_back("µs/point");
  }
  return Table(std::move(header));
}

int bench_main(const char* name, int argc, char** argv, int (*run)(int, char**)) {
  restart_with_huge_pages(argv);  // both as the CLI does, so the benches time what a user's draw costs
  keep_freed_memory();
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << name << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace pcsketch::bench
