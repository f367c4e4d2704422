// Errors a user can act on: each names the input (a file, an option) and what is wrong with it.
//
// Stages throw these at the boundary (io, CLI); the CLI prints the message and exits non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace ramap {

class InputError : public std::runtime_error {
 public:
  // `source` is what was being read (usually a path), `problem` what is wrong with it.
  InputError(const std::string& source, const std::string& problem)
      : std::runtime_error(source + ": " + problem), source_(source) {}

  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

}  // namespace ramap
