// Byte arithmetic and messages for the load limits (see limits.h).
#include "mjcf/limits.h"

#include <cstdio>
#include <limits>

namespace simlab::mjcf {

uint64_t MulBytes(uint64_t count, uint64_t each) {
  uint64_t out = 0;
  if (__builtin_mul_overflow(count, each, &out)) return std::numeric_limits<uint64_t>::max();
  return out;
}

uint64_t AddBytes(uint64_t a, uint64_t b) {
  uint64_t out = 0;
  if (__builtin_add_overflow(a, b, &out)) return std::numeric_limits<uint64_t>::max();
  return out;
}

std::string ByteSize(uint64_t bytes) {
  // The largest unit that keeps the number at 1 or more, one decimal.
  static const char* kUnits[] = {"bytes", "KB", "MB", "GB", "TB", "PB", "EB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024 && unit < 6) {
    value /= 1024;
    unit++;
  }
  char text[32];
  if (unit == 0) {
    std::snprintf(text, sizeof(text), "%llu bytes", static_cast<unsigned long long>(bytes));
  } else {
    std::snprintf(text, sizeof(text), "%.1f %s", value, kUnits[unit]);
  }
  return text;
}

std::string AttrText(const std::string& name, const std::string& value) {
  return name + "=\"" + value + "\"";
}

std::string OverBudget(const std::string& request, uint64_t bytes, const std::string& what,
                       uint64_t budget, const char* budget_of) {
  std::string size = bytes == std::numeric_limits<uint64_t>::max() ? "more than 16 EB"
                                                                   : ByteSize(bytes);
  return request + " asks for " + size + " of " + what + ", over the " + ByteSize(budget) +
         " budget of " + budget_of;
}

}  // namespace simlab::mjcf
