// The device commands' own option syntax (runtime/cli/device_args.hpp): a --timeout outside
// its range is an error, never clamped.
#include <gtest/gtest.h>

#include "runtime/cli/device_args.hpp"

namespace seqc::cli {
namespace {

TEST(DeviceArgs, Timeouts) {
  EXPECT_EQ(*parse_timeout("250ms"), std::chrono::milliseconds(250));
  EXPECT_EQ(*parse_timeout("2s"), std::chrono::seconds(2));
  EXPECT_FALSE(parse_timeout("0ms"));
  EXPECT_FALSE(parse_timeout("2h"));
}

}  // namespace
}  // namespace seqc::cli
