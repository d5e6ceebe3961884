#include "runtime/transport/port_messages.hpp"

#include <cerrno>
#include <cstring>

#include <grp.h>
#include <sys/stat.h>

namespace seqc::transport {

std::string port_in_use_message(std::string_view path) {
  return std::string(path) +
         " is in use by another program (another seqc, a serial monitor or ModemManager); "
         "close it and try again";
}

bool is_hidraw_path(std::string_view path) { return path.starts_with("/dev/hidraw"); }

std::string permission_denied_message(std::string_view path,
                                      const std::optional<std::string>& group) {
  std::string out = "permission denied opening " + std::string(path) + "\n";
  if (is_hidraw_path(path)) {
    out +=
        "  hint: install seqc's udev rule so your login can use the controller:\n"
        "    sudo cp scripts/udev/99-seqc-lobot.rules /etc/udev/rules.d/\n"
        "    sudo udevadm control --reload-rules && sudo udevadm trigger\n"
        "  then unplug and replug the controller (see docs/ports.md)";
    return out;
  }
  // Serial devices belong to the dialout group on Debian, Ubuntu and Fedora (uucp on Arch).
  std::string g =
      group && !group->empty() && *group != "root" && *group != "tty" ? *group : "dialout";
  out += "  hint: add yourself to the '" + g + "' group, then log out and back in:\n";
  out += "    sudo usermod -aG " + g + " $USER";
  return out;
}

std::string no_such_port_message(std::string_view path) {
  return "no such port " + std::string(path) +
         " (is the controller plugged in? `seqc ports` lists what is connected)";
}

std::string open_failure_message(std::string_view path, int error_number) {
  return "cannot open " + std::string(path) + ": " + std::strerror(error_number);
}

std::string describe_open_errno(std::string_view path, int error_number,
                                const std::optional<std::string>& group) {
  switch (error_number) {
    case EACCES:
    case EPERM:
      return permission_denied_message(path, group);
    case EBUSY:
    case EWOULDBLOCK:
      return port_in_use_message(path);
    case ENOENT:
    case ENODEV:
    case ENXIO:
      return no_such_port_message(path);
    default:
      return open_failure_message(path, error_number);
  }
}

std::optional<std::string> owning_group(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  // getgrgid_r: no shared static buffer.
  struct group gr {};
  struct group* found = nullptr;
  char buf[4096];
  if (::getgrgid_r(st.st_gid, &gr, buf, sizeof buf, &found) != 0 || found == nullptr) {
    return std::nullopt;
  }
  return std::string(found->gr_name);
}

}  // namespace seqc::transport
