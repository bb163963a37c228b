#pragma once
/// \file error.hpp
/// The meridian::Error hierarchy. Every error carries an optional context
/// (file, line, field) so a user sees where bad input came from.

#include <optional>
#include <stdexcept>
#include <string>

namespace meridian {

/// Where an error arose. Empty members are unknown.
struct ErrorContext {
  std::string file;           ///< path of the input file
  std::optional<int> line;    ///< 1-based line in that file
  std::string field;          ///< dotted field path, e.g. "determinations[2].crossings[0].times_s"
};

/// Base of all errors thrown by Meridian.
class Error : public std::runtime_error {
 public:
  explicit Error(std::string message, ErrorContext context = {});

  /// The message without context.
  const std::string& message() const noexcept { return message_; }
  const ErrorContext& context() const noexcept { return context_; }

  /// Fill in context known by an outer layer (a reader knows the file, a
  /// loop knows the element index). Unknown members are filled; a field is
  /// prefixed with `field_prefix` ("a.b" + "c" → "a.b.c", "a" + "[2]" → "a[2]").
  void add_context(const std::string& file, std::optional<int> line = std::nullopt,
                   const std::string& field_prefix = {});

  /// Replace the whole context by where the bad value really is: the library's field path
  /// ("dr[12].speed_m_s") becomes the file, line and column the user wrote
  /// ("dr.csv", 14, "speed"). Used by io::SourceMap; catch by reference, relocate and
  /// `throw;`, so the error keeps its class (InputError stays InputError, exit codes with it).
  void relocate(ErrorContext where);

  /// "file:line: field: message" with the unknown parts left out.
  const char* what() const noexcept override { return full_.c_str(); }

 private:
  void rebuild();
  std::string message_;
  ErrorContext context_;
  std::string full_;
};

/// Invalid user input: a missing, contradictory or out-of-range value.
class InputError : public Error {
 public:
  using Error::Error;
};

/// A file or string that cannot be parsed (syntax, truncation, bad number).
class ParseError : public InputError {
 public:
  using InputError::InputError;
};

/// A numerical failure: singular normal matrix, no convergence, negative
/// variance component, a level the model never reaches.
class NumericalError : public Error {
 public:
  using Error::Error;
};

/// Operating-system level failure to read or write a file.
class IoError : public Error {
 public:
  using Error::Error;
};

}  // namespace meridian
