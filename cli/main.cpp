// pcsketch: sketch drawings from raw point clouds (cli/run_cli.cpp).

#include "run_cli.h"

int main(int argc, char** argv) {
  pcsketch::cli::install_interrupt_handlers();
  return pcsketch::cli::run_cli(argc, argv);
}
