#include "meridian/core/error.hpp"

#include <utility>

namespace meridian {

Error::Error(std::string message, ErrorContext context)
    : std::runtime_error(message), message_(std::move(message)), context_(std::move(context)) {
  rebuild();
}

void Error::add_context(const std::string& file, std::optional<int> line,
                        const std::string& field_prefix) {
  if (context_.file.empty()) context_.file = file;
  if (!context_.line) context_.line = line;
  if (!field_prefix.empty()) {
    if (context_.field.empty())
      context_.field = field_prefix;
    else if (context_.field.front() == '[')
      context_.field.insert(0, field_prefix);
    else
      context_.field.insert(0, field_prefix + ".");
  }
  rebuild();
}

void Error::relocate(ErrorContext where) {
  context_ = std::move(where);
  rebuild();
}

void Error::rebuild() {
  std::string s;
  if (!context_.file.empty()) {
    s += context_.file;
    if (context_.line) s.append(":").append(std::to_string(*context_.line));
    s.append(": ");
  } else if (context_.line) {
    s.append("line ").append(std::to_string(*context_.line)).append(": ");
  }
  if (!context_.field.empty()) s.append(context_.field).append(": ");
  s += message_;
  full_ = std::move(s);
}

}  // namespace meridian
