// pcsketch sample MESH -n N [--noise SIGMA] [--seed S] [--keep-normals] -o OUT.ply: clouds of any size from a mesh.

#include <cstdio>
#include <string>

#include "commands.h"
#include "options.h"
#include "pcsketch/io/ply.h"
#include "pcsketch/io/read_cloud.h"
#include "pcsketch/io/sample_mesh.h"

namespace pcsketch::cli {
namespace {

struct SampleArgs {
  std::string mesh_path;
  std::string out_path;
  io::SampleOptions sample;
  bool ascii = false;
};

void run_sample(const SampleArgs& args) {
  check_output_path("--output", args.out_path);
  const Mesh mesh = io::read_mesh(args.mesh_path);
  const PointCloud cloud = io::sample_mesh(mesh, args.sample);
  io::PlyWriteOptions write{.format = args.ascii ? io::PlyFormat::Ascii : io::PlyFormat::BinaryLittleEndian};
  write.comments.push_back("pcsketch sample " + args.mesh_path + " -n " + std::to_string(args.sample.n) + " --noise " +
                           std::to_string(args.sample.noise_sigma_factor) + " --outliers " +
                           std::to_string(args.sample.outlier_fraction) + " --outlier-clump " +
                           std::to_string(args.sample.outlier_clump) + " --seed " +
                           std::to_string(args.sample.seed));
  io::write_ply(args.out_path, cloud, {}, write);
  std::printf("wrote %zu points sampled from %zu faces of %s to %s\n", cloud.size(), mesh.faces.size(),
              args.mesh_path.c_str(), args.out_path.c_str());
}

}  // namespace

void add_sample_command(CLI::App& app, const GlobalOptions&) {
  auto args = std::make_shared<SampleArgs>();
  CLI::App* cmd = app.add_subcommand("sample", "Area-uniform random samples of a mesh's surface, written as PLY");
  cmd->add_option("MESH", args->mesh_path, "Triangle or polygon mesh: OFF, OBJ or PLY with faces")->required();
  cmd->add_option("-n", args->sample.n, "Number of samples")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1}, std::size_t{0xffffffff}));
  cmd->add_option("--noise", args->sample.noise_sigma_factor,
                  "Gaussian noise sigma as a fraction of the bounding-box diagonal (0.001 = 0.1%)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--outliers", args->sample.outlier_fraction,
                  "Stray points added, as a fraction of n, uniform in the bounding box grown by 10% of the diagonal")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--outlier-clump", args->sample.outlier_clump,
                  "Outliers in clumps of this many points (1: isolated points)")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000000}));
  cmd->add_option("--seed", args->sample.seed, "Random seed: same seed, same cloud")->capture_default_str();
  cmd->add_flag("--keep-normals", args->sample.keep_normals,
                "Store each sample's face normal (a raw scan has none, so the default is off)");
  cmd->add_flag("--ascii", args->ascii, "Write ascii PLY instead of binary little-endian");
  cmd->add_option("-o,--output", args->out_path, "Output PLY file")->required();
  cmd->callback([args] { run_sample(*args); });
}

}  // namespace pcsketch::cli
