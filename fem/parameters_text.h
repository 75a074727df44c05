#pragma once
// The FEM section of a case file from fem::Parameters: what a derived FE model (`dembridge
// verify`, `dembridge compare`) ran, written for the user to read and rerun with `dembridge run`.
// Every key of declare_fem_parameters is written; numbers in 17 significant digits, so that
// parse_parameters gives back the same Parameters bit for bit.
#include "fem/parameters.h"
#include <string>

namespace dembridge::fem
{
/// The Parameters of a freshly declared FEM section: every key at its documented default.
Parameters default_parameters();

/// "set Mode = fem" and the whole FEM section of @p p, after a '#' line per entry of @p header.
std::string case_file_text(const Parameters& p, const std::vector<std::string>& header = {});

/// Shortest text that reads back as the same double (17 significant digits at most).
std::string number_text(double value);
} // namespace dembridge::fem
