#pragma once
// The filter's options from Python keyword arguments: the thin layer between
// pliant.Filter / pliant.filter_log and estimation::FilterOptions, whose
// fields may change (one table in filter_options.cpp names those bound).

#include <pybind11/pybind11.h>

#include "pliant/estimation/filter_options.h"

namespace pliant::python {

/// FilterOptions with the given fields set (names as FilterOptions' fields,
/// units in their names). Throws io::InputError for an unknown name, a value
/// of the wrong kind, or options that fail FilterOptions::IsValid.
estimation::FilterOptions FilterOptionsFrom(const pybind11::dict& options);

/// Every bound option with its default (NaN: chosen from the parameters or
/// other options, filter_options.h).
pybind11::dict FilterOptionDefaults();

}  // namespace pliant::python
