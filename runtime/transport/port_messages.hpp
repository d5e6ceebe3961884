// What seqc tells a person when a port cannot be opened. Kept apart from the system calls so
// every message can be tested without the failure it describes.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace seqc::transport {

// "/dev/ttyUSB0 is in use by another program ...".
std::string port_in_use_message(std::string_view path);

// Permission denied on `path`, with how to fix it: the dialout group (or `group`, the group that
// owns the device when known) for serial devices, the udev rule for hidraw devices.
std::string permission_denied_message(std::string_view path,
                                      const std::optional<std::string>& group);

// "no such port /dev/ttyUSB0 ..." with a pointer to `seqc ports`.
std::string no_such_port_message(std::string_view path);

// Any other open failure: "cannot open PATH: STRERROR".
std::string open_failure_message(std::string_view path, int error_number);

// Chooses among the messages above for an errno from open()/flock()/ioctl().
// `group` is looked up by the caller (stat + getgrgid) only for EACCES/EPERM.
std::string describe_open_errno(std::string_view path, int error_number,
                                const std::optional<std::string>& group);

// The name of the group owning `path`, when it can be found.
std::optional<std::string> owning_group(const std::string& path);

// True for /dev/hidraw* device nodes.
bool is_hidraw_path(std::string_view path);

}  // namespace seqc::transport
