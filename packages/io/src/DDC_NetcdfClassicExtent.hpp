// How many bytes a netCDF classic file (CDF-1, CDF-2, CDF-5: the container of
// most Exodus II files) must have, from its header: the check that tells a
// file cut short or with a corrupt header from a whole one before the netCDF
// library opens it (it reads zeros past the end of a short file).
#pragma once

#include <string>

namespace ddc {

/// The extent of the data a classic netCDF header declares.
struct NetcdfClassicExtent {
  bool classic = false;  ///< the file starts with "CDF" 1, 2 or 5
  bool readable = true;  ///< false: the header itself is cut short or malformed (`problem` says where)
  double end = 0.0;      ///< the byte where the last variable's data ends
  std::string variable;  ///< the variable whose data ends there
  std::string problem;   ///< !readable: what could not be read
};

/// Reads the header of `file` (netCDF Classic Format Specification,
/// https://docs.unidata.ucar.edu/netcdf-c/current/file_format_specifications.html):
/// for every variable its type, shape and begin offset; the data of a
/// fixed-size variable ends at begin + its size, that of the record
/// variables at the first record's begin + numrecs times the record size
/// (without the padding to 4 bytes: a bound a whole file always meets). Not
/// a classic file: classic = false.
NetcdfClassicExtent netcdfClassicExtent(const std::string& file);

}  // namespace ddc
