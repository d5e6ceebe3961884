// HidBackend on the system's hidapi (hidraw backend on Linux).
#pragma once

#include <memory>

#include "runtime/transport/hid_backend.hpp"

namespace seqc::transport {

// Calls hid_init() when built; hid_exit() once it and every device it opened are gone.
class HidapiBackend final : public HidBackend {
 public:
  HidapiBackend();

  Result<std::vector<HidDeviceInfo>> enumerate(std::uint16_t vendor_id,
                                               std::uint16_t product_id) override;
  // For /dev/hidraw* paths the device node is also opened and flock()ed, so a second seqc on
  // the same controller fails at once with "... is in use by another program" (hidraw itself
  // lets any number of programs open a device).
  Result<std::unique_ptr<HidDevice>> open(const std::string& path) override;

  struct Library;

 private:
  std::shared_ptr<Library> library_;
};

}  // namespace seqc::transport
