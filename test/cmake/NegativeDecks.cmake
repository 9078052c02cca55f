# Decks of the negative cases made at configure time into ${DDC_DECKS}
# (@DECKS@ in test/negative_cases.txt): one Gmsh deck per mesh file, a deck
# with a 1 MB value and one nested 100000 levels deep (too large, or too odd,
# to keep in the repository).

# ddc_gmsh_deck(<out> <msh> [<element type>]): the deck of one body read
# from <msh> (inputs/negative/gmsh_body.xml.in), of Quad4 elements unless an
# element type is given.
function(ddc_gmsh_deck out msh)
  set(element Quad4)
  if(ARGC GREATER 2)
    set(element ${ARGV2})
  endif()
  file(READ ${DDC_INPUTS}/negative/gmsh_body.xml.in t)
  string(REPLACE "@MSH@" "${msh}" t "${t}")
  string(REPLACE "@ELEMENT@" "${element}" t "${t}")
  file(WRITE ${out} "${t}")
endfunction()

ddc_gmsh_deck(${DDC_DECKS}/gmsh_missing.xml ${DDC_INPUTS}/negative/no_such_mesh.msh)
ddc_gmsh_deck(${DDC_DECKS}/gmsh_v22.xml ${PROJECT_SOURCE_DIR}/packages/io/test/data/version22.msh)
ddc_gmsh_deck(${DDC_DECKS}/gmsh_inverted.xml ${DDC_INPUTS}/data/inverted.msh)
ddc_gmsh_deck(${DDC_DECKS}/gmsh_directory.xml ${DDC_INPUTS}/negative)
ddc_gmsh_deck(${DDC_DECKS}/gmsh_inverted_hex.xml ${DDC_INPUTS}/data/inverted_hex.msh Hex8)
ddc_gmsh_deck(${DDC_DECKS}/gmsh_prism.xml ${DDC_INPUTS}/data/prism.msh Hex8)

# A 1 MB value in place of the generator's name.
string(REPEAT "b" 1000000 _long)
file(READ ${DDC_INPUTS}/small_block.xml _deck)
string(REPLACE "value=\"Rectangle\"" "value=\"${_long}\"" _deck "${_deck}")
file(WRITE ${DDC_DECKS}/long_value.xml "${_deck}")
unset(_long)
unset(_deck)

# Nesting beyond the limit (32): 100000 levels.
string(REPEAT "<ParameterList name=\"a\">" 100000 _open)
string(REPEAT "</ParameterList>" 100000 _close)
file(WRITE ${DDC_DECKS}/deep_nesting.xml "<ParameterList name=\"DDContact\">\n${_open}${_close}\n</ParameterList>\n")
unset(_open)
unset(_close)
