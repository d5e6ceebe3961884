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
        "  hint: install seqc's udev rule so your login can use the controller (the .deb\n"
        "  installs it as /usr/lib/udev/rules.d/70-seqc.rules); from a source tree:\n"
        "    sudo cp scripts/udev/70-seqc.rules /etc/udev/rules.d/\n"
        "    sudo udevadm control --reload-rules && sudo udevadm trigger\n"
        "  then unplug and replug the controller (see docs/ports.md)";
    return out;
  }
  // Name the group the node really belongs to; when that says nothing useful (root, tty, or
  // unknown), give the group serial adapters belong to on Debian, Ubuntu and Fedora.
  const bool owned = group && !group->empty() && *group != "root" && *group != "tty";
  const std::string g = owned ? *group : "dialout";
  out += "  hint: " +
         (owned ? std::string(path) + " belongs to the '" + g + "' group"
                : std::string("serial ports usually belong to the 'dialout' group")) +
         "; add yourself to it, then log out and back in:\n";
  out += "    sudo usermod -aG " + g + " $USER\n";
  out +=
      "  (or install seqc's udev rule, 70-seqc.rules, which gives the user at the machine\n"
      "  access to the usual USB serial adapters; see docs/ports.md)";
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
