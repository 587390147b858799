#pragma once
// The InputError a callable throws, for tests that check an error's where() and fix(): a test failure (and an
// empty error) when it throws none.
#include <gtest/gtest.h>

#include "pounding/core/error.hpp"

namespace pounding::testdata {

template <class F>
InputError input_error(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", "", "");
}

}  // namespace pounding::testdata
