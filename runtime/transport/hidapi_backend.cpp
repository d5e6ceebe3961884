#include "runtime/transport/hidapi_backend.hpp"

#include <cerrno>
#include <cstring>
#include <cwchar>

#include <fcntl.h>
#include <hidapi.h>
#include <sys/file.h>
#include <unistd.h>

#include "runtime/transport/port_messages.hpp"

namespace seqc::transport {

struct HidapiBackend::Library {
  Library() : init_result(hid_init()) {}
  ~Library() { hid_exit(); }
  Library(const Library&) = delete;
  Library& operator=(const Library&) = delete;
  int init_result;
};

namespace {

// hidapi hands out wchar_t strings (UTF-32 on Linux); seqc prints UTF-8.
std::string to_utf8(const wchar_t* text) {
  std::string out;
  if (text == nullptr) return out;
  for (; *text != L'\0'; ++text) {
    auto c = static_cast<std::uint32_t>(*text);
    if (c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) c = 0xFFFD;
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xE0 | (c >> 12));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (c >> 18));
      out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return out;
}

std::string error_text(hid_device* dev) {
  std::string text = to_utf8(hid_error(dev));
  return text.empty() ? "unknown hidapi error" : text;
}

class HidapiDevice final : public HidDevice {
 public:
  HidapiDevice(hid_device* dev, int lock_fd, std::string path,
               std::shared_ptr<HidapiBackend::Library> library)
      : dev_(dev), lock_fd_(lock_fd), path_(std::move(path)), library_(std::move(library)) {}
  ~HidapiDevice() override {
    hid_close(dev_);
    if (lock_fd_ >= 0) ::close(lock_fd_);
  }
  HidapiDevice(const HidapiDevice&) = delete;
  HidapiDevice& operator=(const HidapiDevice&) = delete;

  Result<std::size_t> write(ByteView report) override {
    int n = hid_write(dev_, report.data(), report.size());
    if (n < 0) return make_error(error_text(dev_));
    return static_cast<std::size_t>(n);
  }

  HidRead read(std::span<std::uint8_t> report, int timeout_ms) override {
    int n = hid_read_timeout(dev_, report.data(), report.size(), timeout_ms);
    if (n > 0) return {HidRead::State::Report, static_cast<std::size_t>(n), {}};
    if (n == 0) return {HidRead::State::Timeout, 0, {}};
    int e = errno;
    std::string text = error_text(dev_);
    // hidapi reports an unplug as a poll error "(device disconnected)" or a failed read;
    // the device node disappearing settles it.
    bool gone = e == ENODEV || e == EIO || text.find("disconnected") != std::string::npos ||
                (is_hidraw_path(path_) && ::access(path_.c_str(), F_OK) != 0);
    return {gone ? HidRead::State::Gone : HidRead::State::Error, 0, text};
  }

 private:
  hid_device* dev_;
  int lock_fd_;
  std::string path_;
  std::shared_ptr<HidapiBackend::Library> library_;
};

}  // namespace

HidapiBackend::HidapiBackend() : library_(std::make_shared<Library>()) {}

Result<std::vector<HidDeviceInfo>> HidapiBackend::enumerate(std::uint16_t vendor_id,
                                                            std::uint16_t product_id) {
  if (library_->init_result != 0) {
    return make_error("cannot start hidapi: " + error_text(nullptr));
  }
  std::vector<HidDeviceInfo> out;
  // NULL means "none found" as well as failure; either way there is nothing to list.
  hid_device_info* list = hid_enumerate(vendor_id, product_id);
  for (hid_device_info* d = list; d != nullptr; d = d->next) {
    out.push_back(HidDeviceInfo{
        .path = d->path ? d->path : "",
        .vendor_id = d->vendor_id,
        .product_id = d->product_id,
        .product = to_utf8(d->product_string),
        .manufacturer = to_utf8(d->manufacturer_string),
        .serial_number = to_utf8(d->serial_number),
        .interface_number = d->interface_number,
    });
  }
  hid_free_enumeration(list);
  return out;
}

Result<std::unique_ptr<HidDevice>> HidapiBackend::open(const std::string& path) {
  if (library_->init_result != 0) {
    return make_error("cannot start hidapi: " + error_text(nullptr));
  }
  int lock_fd = -1;
  if (is_hidraw_path(path)) {
    lock_fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (lock_fd < 0) {
      int e = errno;
      bool denied = e == EACCES || e == EPERM;
      return make_error(describe_open_errno(path, e, denied ? owning_group(path) : std::nullopt));
    }
    if (::flock(lock_fd, LOCK_EX | LOCK_NB) != 0) {
      int e = errno;
      ::close(lock_fd);
      return make_error(e == EWOULDBLOCK ? port_in_use_message(path)
                                         : "cannot lock " + path + ": " + std::strerror(e));
    }
  }
  errno = 0;
  hid_device* dev = hid_open_path(path.c_str());
  if (dev == nullptr) {
    int e = errno;
    std::string text = error_text(nullptr);
    if (lock_fd >= 0) ::close(lock_fd);
    if (e == EACCES || e == EPERM || text.find(std::strerror(EACCES)) != std::string::npos) {
      return make_error(permission_denied_message(path, owning_group(path)) +
                        "\n  (hidapi: " + text + ")");
    }
    return make_error("cannot open HID device " + path + ": " + text);
  }
  return std::unique_ptr<HidDevice>(new HidapiDevice(dev, lock_fd, path, library_));
}

}  // namespace seqc::transport
