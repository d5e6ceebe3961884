// Everything a subcommand may touch outside itself, passed in (DEVELOPERS.md rule 2), so
// tests run subcommands in-process with string streams, a manual clock and fake ports.
#pragma once

#include <atomic>
#include <iosfwd>

#include "compiler/source/source.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::cli {

struct Context {
  std::ostream& out;              // data
  std::ostream& err;              // diagnostics, progress, "seqc: error: ..."
  io::Clock& clock;
  compiler::FileReader& files;
  bool err_is_terminal = false;   // progress bar vs plain lines
  // Set by the SIGINT handler; long-running commands poll it and stop cleanly.
  const std::atomic<bool>* interrupted = nullptr;
};

}  // namespace seqc::cli
