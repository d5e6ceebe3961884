#include "runtime/transport/hid_backend.hpp"

#include <algorithm>

namespace seqc::transport {

Result<std::vector<HidDeviceInfo>> find_lobot_devices(HidBackend& backend) {
  auto all = backend.enumerate(kLobotVendorId, kLobotProductId);
  if (!all) return all.error();
  std::vector<HidDeviceInfo> out;
  for (auto& d : *all) {
    // Backends may return more than asked for (a fake, or a future wildcard): filter on all three.
    if (d.vendor_id == kLobotVendorId && d.product_id == kLobotProductId &&
        d.product == kLobotProduct &&
        std::none_of(out.begin(), out.end(), [&](const auto& o) { return o.path == d.path; })) {
      out.push_back(std::move(d));
    }
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.path < b.path; });
  return out;
}

}  // namespace seqc::transport
