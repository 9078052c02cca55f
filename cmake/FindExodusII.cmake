# FindExodusII: the Exodus II library of the SEACAS project on NetCDF
# (Debian: libexodusii-dev, Exodus 6.02, libexoIIv2c). Defines
# ExodusII::ExodusII. DDContact writes its results in Exodus II with it
# (doc/user-guide.md, "The output directory").
find_path(EXODUSII_INCLUDE_DIR exodusII.h)
find_library(EXODUSII_LIBRARY NAMES exoIIv2c exodus)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(ExodusII REQUIRED_VARS EXODUSII_LIBRARY EXODUSII_INCLUDE_DIR)
if(ExodusII_FOUND AND NOT TARGET ExodusII::ExodusII)
  add_library(ExodusII::ExodusII INTERFACE IMPORTED)
  set_target_properties(ExodusII::ExodusII PROPERTIES
    INTERFACE_LINK_LIBRARIES "${EXODUSII_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${EXODUSII_INCLUDE_DIR}")
endif()
mark_as_advanced(EXODUSII_INCLUDE_DIR EXODUSII_LIBRARY)
