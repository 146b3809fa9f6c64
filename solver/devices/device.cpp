#include "solver/devices/device.h"

#include <cstdio>

namespace lcs {

std::string Device::deck_name(char letter, const std::string& name) {
  if (!name.empty() && name[0] == letter && name.find('.') == std::string::npos) return name;
  return std::string(1, letter) + "_" + name;
}

std::string Device::number(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g", x);
  return buf;
}

}  // namespace lcs
