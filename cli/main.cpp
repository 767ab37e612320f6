// pcsketch: sketch drawings from raw point clouds (cli/run_cli.cpp).

#include "pcsketch/core/allocator.h"
#include "run_cli.h"

int main(int argc, char** argv) {
  pcsketch::restart_with_huge_pages(argv);
  pcsketch::keep_freed_memory();
  pcsketch::cli::install_interrupt_handlers();
  return pcsketch::cli::run_cli(argc, argv);
}
