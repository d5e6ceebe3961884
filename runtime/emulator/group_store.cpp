#include "runtime/emulator/group_store.hpp"

#include <type_traits>
#include <variant>

namespace seqc::emu {

const std::optional<std::vector<lsc::GroupAction>>& GroupStore::group(std::uint8_t group) const {
  return groups_[group];
}

void GroupStore::store(std::uint8_t group, std::vector<lsc::GroupAction> actions) {
  if (group < kGroupCount) groups_[group] = std::move(actions);
}

bool GroupStore::room_for(std::uint8_t group, std::size_t actions) const {
  if (group >= limits_.groups) return false;
  std::size_t others = 0;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    if (g != group && groups_[g]) others += groups_[g]->size();
  }
  return others + actions <= limits_.flash_actions;
}

void GroupStore::erase(std::uint8_t group) { groups_[group].reset(); }

void GroupStore::erase_all() {
  for (auto& g : groups_) g.reset();
}

std::optional<GroupDownloader::Outcome> GroupDownloader::handle(const lsc::Frame& frame,
                                                                GroupStore& store) {
  if (frame.data.empty() || frame.data[0] < 1 || frame.data[0] > 5) return std::nullopt;
  Outcome out;
  out.ack.step = frame.data[0];
  const bool is_retry = out.ack.step >= 2 && last_accepted_ && *last_accepted_ == frame.data;
  bool accepted = is_retry;
  if (!is_retry) {
    auto request = lsc::decode_group_download(frame);
    accepted = request.ok() && accept(*request, store);
    if (accepted) last_accepted_ = frame.data;
  }
  out.ack.status = accepted ? 0 : 1;
  if (accepted && out.ack.step == 1) out.work = Work::FlashErase;
  if (accepted && out.ack.step == 4) out.work = Work::FlashWrite;
  return out;
}

bool GroupDownloader::accept(const lsc::Request& request, GroupStore& store) {
  return std::visit(
      [&](const auto& m) -> bool {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, lsc::GroupDownloadOpen>) {
          if (m.group >= kGroupCount || m.block_counts.empty() ||
              m.block_counts.size() > lsc::kMaxBlocks) {
            return false;
          }
          std::size_t announced = 0;
          for (auto n : m.block_counts) {
            if (n == 0) return false;
            announced += n;
          }
          if (!store.room_for(m.group, announced)) return false;
          store.erase(m.group);
          session_ = Session{};
          session_->group = m.group;
          session_->counts = m.block_counts;
          return true;
        } else if constexpr (std::is_same_v<T, lsc::GroupDownloadSize>) {
          if (!session_ || session_->group != m.group || session_->phase != Phase::Sizes ||
              m.block != session_->sizes_done || m.count != session_->counts[m.block]) {
            return false;
          }
          if (++session_->sizes_done == session_->counts.size()) session_->phase = Phase::Blocks;
          return true;
        } else if constexpr (std::is_same_v<T, lsc::GroupDownloadBlocks>) {
          if (!session_ || session_->group != m.group || session_->phase != Phase::Blocks ||
              m.block_count != session_->counts.size()) {
            return false;
          }
          session_->phase = Phase::Actions;
          return true;
        } else if constexpr (std::is_same_v<T, lsc::GroupDownloadAction>) {
          if (!session_ || session_->group != m.group || session_->phase != Phase::Actions ||
              m.block != session_->block || m.index != session_->index) {
            return false;
          }
          session_->actions.push_back(lsc::GroupAction{m.time_ms, m.servos});
          if (++session_->index == session_->counts[session_->block]) {
            session_->index = 0;
            if (++session_->block == session_->counts.size()) session_->phase = Phase::Complete;
          }
          return true;
        } else if constexpr (std::is_same_v<T, lsc::GroupDownloadClose>) {
          if (!session_ || session_->group != m.group || session_->phase != Phase::Complete) {
            return false;
          }
          store.store(m.group, std::move(session_->actions));
          session_.reset();
          return true;
        } else {
          return false;  // decode_group_download only yields the five step types
        }
      },
      request);
}

void GroupDownloader::abort() {
  session_.reset();
  last_accepted_.reset();
}

std::optional<std::uint8_t> GroupDownloader::active_group() const {
  if (!session_) return std::nullopt;
  return session_->group;
}

}  // namespace seqc::emu
