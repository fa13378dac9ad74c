// One error policy: every problem with the caller's input is a plunge::Error.
// The Python layer turns it into ValueError, the CLI into one line on stderr.
#pragma once
#include <stdexcept>
#include <string>

namespace plunge {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace plunge
