// One error policy, two kinds. Every problem with the caller's input is a
// plunge::Error: the Python layer turns it into ValueError, the CLI into one
// line on stderr and exit status 2. A fault of the planner itself (a bug,
// never the input's) is a plunge::InternalError: RuntimeError in Python, exit
// status 3 and "please report" from the CLI.
#pragma once
#include <stdexcept>
#include <string>

namespace plunge {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

}  // namespace plunge
