// `seqc compile --emit` through each board's row: the form its frames are written in, and how
// a listing says the group is stored.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "compiler/compile.hpp"
#include "runtime/boards/board.hpp"
#include "runtime/io/disk.hpp"
#include "tests/boards/board_test_util.hpp"

namespace seqc::boards {
namespace {

using test_support::compile_example;

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

TEST(BoardRender, XarmListingCountsBlocks) {
  const compiler::CompileOutput walk = compile_example("../tests/data/walk-joints.yaml");
  auto listing = board_for(walk).render(walk, Emit::Listing, 0);
  ASSERT_TRUE(listing.ok()) << listing.error().message;
  EXPECT_EQ(first_line(*listing).substr(0, 54),
            "# robot xarm, group 0: 27 actions in 1 block, 31 frame");
}

TEST(BoardRender, XarmHexIsOneFramePerLine) {
  const compiler::CompileOutput walk = compile_example("../tests/data/walk-joints.yaml");
  auto hex = board_for(walk).render(walk, Emit::Hex, 0);
  ASSERT_TRUE(hex.ok());
  EXPECT_EQ(std::count(hex->begin(), hex->end(), '\n'), 31);
  EXPECT_EQ(hex->substr(0, 6), "55 55 ");
}

TEST(BoardRender, Lsc6ListingNamesItsDialect) {
  const compiler::CompileOutput learm = compile_example("learm.yaml");
  auto listing = board_for(learm).render(learm, Emit::Listing, 0);
  ASSERT_TRUE(listing.ok()) << listing.error().message;
  EXPECT_EQ(first_line(*listing).substr(0, 60),
            "# robot learm, group 0: 36 actions (LSC-6 dialect), 36 frame");
}

TEST(BoardRender, TheCarHasAStreamNotAGroup) {
  const compiler::CompileOutput car = compile_example("car-dance.yaml");
  const Board& board = board_for(car);
  EXPECT_EQ(board.plan, nullptr);
  auto hex = board.render(car, Emit::Hex, 0);
  ASSERT_TRUE(hex.ok());
  // Each line: the send time in ms right-aligned in 6 columns, " ms  ", then the frame.
  EXPECT_EQ(hex->substr(0, 16), "     0 ms  ff fe");
}

}  // namespace
}  // namespace seqc::boards
