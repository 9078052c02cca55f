# Output (doc/user-guide.md, "The output directory"): never destroy what
# DDContact did not write, writes that cannot half-happen, one run per
# directory; Exodus II results read back by independent readers; Exodus II
# meshes read in.

# tools/output_directory_cases.sh (fault injection through
# DDCONTACT_FAULT_INJECTION): a failing write / sync / close / create at each
# file of a result; the process killed at each stage of a run and its commit
# and the next run's recovery; two concurrent runs (twice the ranks at once);
# foreign directories and files. Every case on 1 and 2 ranks, every rank's
# exit status checked.
foreach(case write-faults kill-stages concurrent foreign)
  foreach(np 1 2)
    set(processors ${np})
    if(case STREQUAL "concurrent")
      set(processors 2)
    endif()
    ddc_add_script_test(output_${case}_np${np} PROCESSORS ${processors} LABELS output negative
      PROPERTIES FAIL_REGULAR_EXPRESSION "FAIL:"
      COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/tools/output_directory_cases.sh
        ${case} ${np} ${DDC_APP} ${DDC_INPUTS}/small_block.xml ${DDC_RUNS}/output_${case}_np${np})
  endforeach()
endforeach()
# A result directory of another user, which this user cannot empty: refused
# at start (it used to exit 0 leaving an undeletable D.old). Runs the second
# run as 'nobody' (needs root and setpriv; skipped otherwise).
foreach(np 1 2)
  ddc_add_script_test(output_foreign_owner_np${np} PROCESSORS ${np} LABELS output negative
    PROPERTIES FAIL_REGULAR_EXPRESSION "FAIL:" SKIP_RETURN_CODE 77
    COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/tools/foreign_owner_case.sh
      ${np} ${DDC_APP} ${DDC_INPUTS}/small_block.xml ${DDC_RUNS}/output_foreign_owner_np${np})
endforeach()

# Exodus II results (Output/Exodus) read back by independent readers, VTK's
# vtkExodusIIReader and meshio (Debian python3-vtk9, python3-meshio: the
# system Python has them): blocks, sets, variables, one time step per history
# row, and every value equal to the VTK output's and history.csv's; the
# element node order checked cell by cell, the side numbering against the
# node sets. Contact in 2-D, the quadratic and tetrahedral cells in 3-D,
# dynamics on 3 ranks.
find_program(DDC_SYSTEM_PYTHON python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT DDC_SYSTEM_PYTHON)
  find_program(DDC_SYSTEM_PYTHON python3)
endif()
# ddc_add_exodus_test(<name> <ranks> <deck> [ddcontact args...]): the run
# (a fixture: results.e and history.csv) and <name>_readers.
function(ddc_add_exodus_test name ranks deck)
  ddc_add_run_test(${name} RANKS ${ranks} FIXTURE
    ARGS ${deck} --set "Output/Exodus=true" --set "Output/VTK Interval=1" --output-dir ${DDC_RUNS}/${name} ${ARGN}
    FILES ${DDC_RUNS}/${name}/results.e LABELS output)
  add_test(NAME ${name}_readers COMMAND ${DDC_SYSTEM_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/tools/check_exodus.py
    ${DDC_RUNS}/${name})
  set_tests_properties(${name}_readers PROPERTIES FIXTURES_REQUIRED ${name} LABELS "system;output")
endfunction()
# On parts of the mesh each rank writes its piece, results.e.P.r, and no
# rank gathers the mesh or its values: the pieces joined by their node and
# element ids are the whole-mesh run's results.e - on as many ranks (the same
# PT-Scotch partition) to round-off, on 4 ranks to the examples'
# rank-independence tolerance (runs in examples.cmake).
foreach(np 2 4)
  set(tolerance 1e-12)
  if(np EQUAL 4)
    set(tolerance 1e-10)
  endif()
  add_test(NAME exodus_pieces_equal_whole_block_3d_np${np} COMMAND ${DDC_SYSTEM_PYTHON}
    ${CMAKE_CURRENT_SOURCE_DIR}/tools/check_exodus_pieces.py ${DDC_RUNS}/ptscotch_whole_block_3d_np2/results.e
    ${DDC_RUNS}/mesh_in_ranges_block_3d_np${np}/results.e ${tolerance})
  set_tests_properties(exodus_pieces_equal_whole_block_3d_np${np} PROPERTIES
    FIXTURES_REQUIRED "ptscotch_whole_block_3d_np2;mesh_in_ranges_block_3d_np${np}" LABELS "system;output")
endforeach()
add_test(NAME exodus_pieces_gmsh_block_in_ranges COMMAND ${DDC_SYSTEM_PYTHON}
  ${CMAKE_CURRENT_SOURCE_DIR}/tools/check_exodus_pieces.py ${DDC_RUNS}/gmsh_block_whole_np3/results.e
  ${DDC_RUNS}/gmsh_block_in_ranges_np3/results.e)
set_tests_properties(exodus_pieces_gmsh_block_in_ranges PROPERTIES
  FIXTURES_REQUIRED "gmsh_block_whole_np3;gmsh_block_in_ranges_np3" LABELS "system;output")
ddc_add_exodus_test(exodus_half_rings 2 ${PROJECT_SOURCE_DIR}/examples/two_half_rings.xml
  --set "Load Stepping/Number of Steps=10")
ddc_add_exodus_test(exodus_arch_Quad9 2 ${PROJECT_SOURCE_DIR}/examples/arch.xml
  --set "Mesh/Bodies/Arch/Element/Type=Quad9")
foreach(cell Hex8 Hex20 Hex27 Tet4 Tet10)
  ddc_add_exodus_test(exodus_block_${cell} 2 ${PROJECT_SOURCE_DIR}/examples/block_3d.xml
    --set "Mesh/Bodies/Block/Element/Type=${cell}")
endforeach()
ddc_add_exodus_test(exodus_bar_impact 3 ${PROJECT_SOURCE_DIR}/examples/bar_impact.xml --set "Dynamics/Final Time=4")

# Exodus II meshes in (Generator = Exodus, doc/user-guide.md "Writing an
# input deck"): a file written by an independent writer
# (tools/write_exodus_mesh.py: netCDF4, not the Exodus II library) from the
# mesh of a run on generated bodies, every body read from it
# (tools/exodus_deck.py), gives the same history as the generated mesh - the
# two half-rings (2-D, contact, FETI-DP on 4 METIS subdomains: the run
# exodus_half_rings above, 10 steps) and the Hertz sphere on its block (3-D,
# 2 steps) - and malformed files fail naming the file and the entity (the
# exodus_mesh_* cases of test/negative_cases.txt, which read the files made
# here).
set(EXO_MESH ${DDC_RUNS}/exodus_mesh)
ddc_add_run_test(exodus_mesh_hertz_generated RANKS 2 FIXTURE
  ARGS ${PROJECT_SOURCE_DIR}/examples/hertz_sphere.xml --set "Load Stepping/Number of Steps=2"
    --set "Output/Exodus=true" --set "Output/VTK=false" --output-dir ${DDC_RUNS}/exodus_mesh_hertz_generated
  FILES ${DDC_RUNS}/exodus_mesh_hertz_generated/results.e LABELS output)
foreach(case half_rings hertz)
  if(case STREQUAL half_rings)
    set(deck ${PROJECT_SOURCE_DIR}/examples/two_half_rings.xml)
    set(steps 10)
    set(source exodus_half_rings)
  else()
    set(deck ${PROJECT_SOURCE_DIR}/examples/hertz_sphere.xml)
    set(steps 2)
    set(source exodus_mesh_hertz_generated)
  endif()
  add_test(NAME exodus_mesh_${case}_files COMMAND sh -c
    "mkdir -p ${EXO_MESH} && ${DDC_SYSTEM_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/tools/write_exodus_mesh.py ${DDC_RUNS}/${source}/results.e ${EXO_MESH}/${case}.e && ${DDC_SYSTEM_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/tools/exodus_deck.py ${deck} ${EXO_MESH}/${case}.xml ${EXO_MESH}/${case}.e")
  set_tests_properties(exodus_mesh_${case}_files PROPERTIES FIXTURES_REQUIRED ${source}
    FIXTURES_SETUP exodus_mesh_${case}_files LABELS "system;output")
  ddc_add_run_test(exodus_mesh_${case} RANKS 2 FIXTURE
    ARGS ${EXO_MESH}/${case}.xml --set "Load Stepping/Number of Steps=${steps}" --set "Output/VTK=false"
      --output-dir ${EXO_MESH}/${case}_read
    FILES ${EXO_MESH}/${case}_read/history.csv LABELS output)
  set_tests_properties(exodus_mesh_${case} PROPERTIES FIXTURES_REQUIRED exodus_mesh_${case}_files)
  add_test(NAME exodus_mesh_${case}_same_results COMMAND compare_history
    ${DDC_RUNS}/${source}/history.csv ${EXO_MESH}/${case}_read/history.csv 1e-12
    step load_factor strain_energy newton_iterations active_contacts contact_force_x contact_force_y external_work)
  set_tests_properties(exodus_mesh_${case}_same_results PROPERTIES
    FIXTURES_REQUIRED "${source};exodus_mesh_${case}" LABELS "system;output")
endforeach()
# An Exodus II mesh read in slabs on 3 ranks (parts of the mesh,
# PT-Scotch: each rank reads a range of the elements and a share of the
# coordinates and sets, none the whole file): block_3d's 1-rank history, to
# the examples' rank-independence tolerance, and the whole-mesh run's
# history on the same 3 ranks and partition, to round-off.
add_test(NAME exodus_mesh_block_files COMMAND sh -c
  "mkdir -p ${EXO_MESH} && ${DDC_SYSTEM_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/tools/write_exodus_mesh.py ${DDC_RUNS}/exodus_block_Hex8/results.e ${EXO_MESH}/block.e && ${DDC_SYSTEM_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/tools/exodus_deck.py ${PROJECT_SOURCE_DIR}/examples/block_3d.xml ${EXO_MESH}/block.xml ${EXO_MESH}/block.e")
set_tests_properties(exodus_mesh_block_files PROPERTIES FIXTURES_REQUIRED exodus_block_Hex8
  FIXTURES_SETUP exodus_mesh_block_files LABELS "system;output")
foreach(mode whole in_ranges)
  ddc_mesh_mode(${mode} parts said)
  ddc_add_run_test(exodus_mesh_block_${mode}_np3 RANKS 3 FIXTURE
    ARGS ${EXO_MESH}/block.xml --set "Partition/Method=PT-Scotch" ${parts}
      --set "Output/VTK=false" --output-dir ${DDC_RUNS}/exodus_mesh_block_${mode}_np3
    FILES ${DDC_RUNS}/exodus_mesh_block_${mode}_np3/history.csv LABELS output
    REGEX "${said}")
  set_tests_properties(exodus_mesh_block_${mode}_np3 PROPERTIES FIXTURES_REQUIRED exodus_mesh_block_files)
endforeach()
ddc_compare_histories(exodus_mesh_block_in_ranges_same_results example_block_3d_np1
  exodus_mesh_block_in_ranges_np3 1e-10 LABELS output)
ddc_compare_histories(exodus_mesh_block_in_ranges_equal_whole exodus_mesh_block_whole_np3
  exodus_mesh_block_in_ranges_np3 1e-12 LABELS output)
# The contact meshes' files read in slabs on 3 ranks: the runs on the
# generated meshes in ranges (contact.cmake), whose ids the files keep -
# history and contact nodes to round-off (0 measured): the half rings (2-D,
# FETI-DP) and the Hertz sphere (3-D, the decomposed element under FETI-DP
# on 8 PT-Scotch subdomains; its "sphere" side set merges three grid sides).
set(EXO_IN_RANGES_half_rings half_rings_feti-dp_np3)
set(EXO_IN_RANGES_hertz hertz_decomposed_feti-dp_np3 --set "Partition/Number of Subdomains=8")
foreach(case half_rings hertz)
  list(POP_FRONT EXO_IN_RANGES_${case} generated)
  ddc_add_run_test(exodus_mesh_${case}_in_ranges_np3 RANKS 3 FIXTURE
    ARGS ${EXO_MESH}/${case}.xml --set "Partition/Method=PT-Scotch" --set "Partition/Mesh On Every Rank=false"
      --set "Output/Contact Nodes=true" --set "Output/VTK=false" ${EXO_IN_RANGES_${case}}
      --output-dir ${DDC_RUNS}/exodus_mesh_${case}_in_ranges_np3
    FILES ${DDC_RUNS}/exodus_mesh_${case}_in_ranges_np3/contact_nodes.csv LABELS output
    REGEX "; no rank held the whole mesh \\(built in ranges of elements\\)")
  set_tests_properties(exodus_mesh_${case}_in_ranges_np3 PROPERTIES FIXTURES_REQUIRED exodus_mesh_${case}_files)
  ddc_compare_histories(exodus_mesh_${case}_in_ranges_equal_generated contact_in_ranges_${generated}
    exodus_mesh_${case}_in_ranges_np3 1e-12 LABELS output)
  ddc_compare_histories(exodus_mesh_${case}_in_ranges_equal_generated_nodes contact_in_ranges_${generated}
    exodus_mesh_${case}_in_ranges_np3 1e-12 FILE contact_nodes.csv LABELS output)
endforeach()
# Malformed files, from the half-rings mesh.
foreach(bad wedge inverted side_element side_number)
  if(bad STREQUAL wedge)
    set(opt --element-type WEDGE6)
  elseif(bad STREQUAL inverted)
    set(opt --invert-element 5)
  elseif(bad STREQUAL side_element)
    set(opt --side-set-element 99999)
  else()
    set(opt --side-number 7)
  endif()
  string(REPLACE ";" " " opt "${opt}")
  add_test(NAME exodus_mesh_malformed_${bad}_file COMMAND sh -c
    "mkdir -p ${EXO_MESH} && ${DDC_SYSTEM_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/tools/write_exodus_mesh.py ${DDC_RUNS}/exodus_half_rings/results.e ${EXO_MESH}/malformed_${bad}.e ${opt}")
  set_tests_properties(exodus_mesh_malformed_${bad}_file PROPERTIES FIXTURES_REQUIRED exodus_half_rings
    FIXTURES_SETUP exodus_mesh_malformed_${bad} LABELS "system;output")
endforeach()

# The meshes of the mesh input negative cases (test/negative_cases.txt, "Mesh
# input and contact set-up"): a conforming two-block Exodus II mesh and its
# broken variants, Gmsh files with bad coordinates (tools/write_mesh_input_cases.py).
add_test(NAME mesh_input_files COMMAND ${DDC_SYSTEM_PYTHON}
  ${CMAKE_CURRENT_SOURCE_DIR}/tools/write_mesh_input_cases.py ${DDC_RUNS}/mesh_input)
set_tests_properties(mesh_input_files PROPERTIES FIXTURES_SETUP mesh_input_files LABELS "system;negative")
