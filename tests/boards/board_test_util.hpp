// What the boards tests share: an example compiled from examples/ as `seqc` compiles it, and the
// answer of a device that says nothing (for AcknowledgingTransport).
#pragma once

#include <string>

#include "compiler/compile.hpp"
#include "runtime/io/disk.hpp"
#include "base/bytes.hpp"

namespace seqc::boards::test_support {

// `name` is a path from examples/ ("walk.yaml", "../tests/data/walk-joints.yaml").
inline compiler::CompileOutput compile_example(const char* name) {
  io::DiskFileReader files;
  return compiler::compile_file(std::string(SEQC_SOURCE_DIR) + "/examples/" + name, files);
}

inline Bytes silent(ByteView) { return {}; }

}  // namespace seqc::boards::test_support
