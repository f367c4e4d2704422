// Errors a user can act on: each names the input (a file, an option) and what is wrong with it;
// and the typed failure of a stage on an input it cannot use.
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

// The input held no component the mapper could reconstruct (too few images connected). The
// command line reports it as any input error; a Python caller gets an empty result and the reason.
class NothingReconstructed : public InputError {
 public:
  using InputError::InputError;
};

// A stage that cannot run on this input (e.g. translation averaging with fewer than two cameras
// connected): the mapper records the reason for the images concerned and goes on with the rest.
class StageFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ramap
