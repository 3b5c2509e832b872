#include "core/error.hpp"

namespace spreadmap {
namespace {

std::string joined(const std::vector<std::string> &all, const std::string &note) {
  std::string text;
  for (const auto &m : all) text += (text.empty() ? "" : "\n") + m;
  if (!note.empty()) text += "\n" + note;
  return text;
}

}  // namespace

Error::Error(const std::vector<std::string> &all, const std::string &note_, int code)
    : std::runtime_error(joined(all, note_)), messages(all), note(note_), exit_code(code) {}

std::string printed(const std::exception &e) {
  const auto *error = dynamic_cast<const Error *>(&e);
  if (!error) return std::string("error: ") + e.what() + "\n";
  // A stop the user asked for is no error: its message says what was kept and how to go on.
  const std::string prefix = error->exit_code == exit_interrupted ? "" : "error: ";
  std::string text;
  for (const auto &m : error->messages) text += prefix + m + "\n";
  if (!error->note.empty()) text += error->note + "\n";
  return text;
}

}  // namespace spreadmap
