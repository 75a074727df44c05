#pragma once
// The plot of `dembridge compare` (app/compare.cc): a Python script (matplotlib) that reads
// comparison.csv and the two crack logs and draws the load-deflection curves of the three models
// and the crack paths side by side. Arguments: comparison.csv, the PNG, a title, the coupled and
// full-DEM crack CSV files, the horizontal and vertical axis (0, 1, 2) of the crack view and the
// vertical extent (m).
namespace dembridge::app
{
extern const char* const compare_plot_script;
}
