// The one way an options struct rejects a value: InputError naming the option as the command line
// spells it, the requirement and the value given ("--Section.option: must be > 0, got -1"). A
// setting no command line option reaches (only code sets it) is named as Struct::field instead,
// so that no message names an option that does not exist (tests/python/test_option_reference.py).
#pragma once

#include <sstream>
#include <string>

#include "ramap/util/error.h"

namespace ramap {

// Throws InputError(option, "must be " + requirement + ", got " + value) unless `ok`. NaN fails
// every comparison, so `ok` written as a comparison rejects it too.
template <typename T>
void CheckOption(bool ok, const std::string& option, const std::string& requirement,
                 const T& value) {
  if (ok) return;
  std::ostringstream got;
  got << value;
  throw InputError(option, "must be " + requirement + ", got " + got.str());
}

}  // namespace ramap
