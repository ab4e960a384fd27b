// A library Error on its way to Python: module.cc translates an ErrorException into
// dynslam.Error carrying the file and line.
#ifndef DYNSLAM_PYTHON_ERRORS_H_
#define DYNSLAM_PYTHON_ERRORS_H_

#include <utility>

#include "dynslam/status.h"

namespace dynslam::python {

struct ErrorException {
  Error error;
};

template <typename T>
T Unwrap(Expected<T> expected) {
  if (!expected.ok()) throw ErrorException{expected.error()};
  return std::move(expected).value();
}

}  // namespace dynslam::python

#endif  // DYNSLAM_PYTHON_ERRORS_H_
