# Checkpoints and restart (doc/user-guide.md, "Checkpoints and restart").
# tools/restart_cases.sh: a run stopped after step k (SIGTERM while step k+1
# is solved, through the test seam and for real from outside; SIGUSR1 to
# mpirun, which forwards it; a deliberate Newton failure) restarts with
# --restart and ends with the uninterrupted run's history.csv, field for
# field but wall_seconds, and the same VTK and Exodus II files byte for
# byte. The two half-rings: the decomposed element under FETI-DP (METIS, 4
# subdomains) and the conventional element under Monolithic, on 1 and 2
# ranks. Monolithic on 2 ranks uses Amesos2 (KLU2 gathered to rank 0):
# MUMPS on several ranks sums contributions in the order messages arrive,
# so two uninterrupted runs already differ (measured: 4e-14 of the peak
# external work; doc/user-guide.md, "Checkpoints and restart"). Restarted
# on another rank count: 1e-10. Corrupted, truncated and foreign
# checkpoints, changes a restart may not make, and no checkpoint: refused,
# nothing changed (these are labelled negative too).
#
# The uninterrupted run of a deck, options and rank count is computed once,
# restart_reference_<variant>, and the cases that stop that run compare with
# it (REFERENCE_RUN).
set(DDC_HALF_RINGS ${PROJECT_SOURCE_DIR}/examples/two_half_rings.xml)
set(DDC_RESTART_CONVENTIONAL --set "Contact/Formulation=Node-To-Segment" --set "Solver/Strategy=Monolithic")
# ddc_add_restart_test(<name> <np> <case> <deck> [REFERENCE <variant>]
#                      [PROCESSORS n] [LABELS l...] [ENVIRONMENT e...] [FIXTURES f...]
#                      [ARGS ddcontact args...])
# REFERENCE: the shared uninterrupted run restart_reference_<variant>
# (or another run named by ENVIRONMENT REFERENCE_RUN=... and FIXTURES).
function(ddc_add_restart_test name np case deck)
  cmake_parse_arguments(X "" "REFERENCE;PROCESSORS" "LABELS;ENVIRONMENT;FIXTURES;ARGS" ${ARGN})
  set(processors ${np})
  if(X_PROCESSORS)
    set(processors ${X_PROCESSORS})
  endif()
  set(environment ${X_ENVIRONMENT})
  set(fixtures ${X_FIXTURES})
  if(X_REFERENCE)
    set(environment REFERENCE_RUN=${DDC_RUNS}/restart_reference_${X_REFERENCE}/reference)
    set(fixtures restart_reference_${X_REFERENCE})
  endif()
  ddc_add_script_test(${name} PROCESSORS ${processors} LABELS restart ${X_LABELS}
    ENVIRONMENT ${environment} FIXTURES ${fixtures} PROPERTIES FAIL_REGULAR_EXPRESSION "FAIL:"
    COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/tools/restart_cases.sh ${case} ${np} ${DDC_APP}
      $<TARGET_FILE:compare_history> ${deck} ${DDC_RUNS}/${name} ${X_ARGS})
endfunction()
# ddc_add_restart_reference(<variant> <np> [ddcontact args...]): the shared
# uninterrupted run of the half-rings.
function(ddc_add_restart_reference variant np)
  ddc_add_restart_test(restart_reference_${variant} ${np} reference ${DDC_HALF_RINGS} ARGS ${ARGN})
  set_tests_properties(restart_reference_${variant} PROPERTIES FIXTURES_SETUP restart_reference_${variant})
endfunction()

foreach(np 1 2)
  ddc_add_restart_reference(feti_np${np} ${np} --set "Output/Exodus=true")
  foreach(case sigterm newton-failure memory-stop)
    ddc_add_restart_test(restart_${case}_feti_np${np} ${np} ${case} ${DDC_HALF_RINGS} REFERENCE feti_np${np}
      ARGS --set "Output/Exodus=true")
  endforeach()
endforeach()
ddc_add_restart_reference(monolithic_np1 1 ${DDC_RESTART_CONVENTIONAL})
ddc_add_restart_reference(monolithic_np2 2 ${DDC_RESTART_CONVENTIONAL} --set "Solver/Linear Solver/Type=Amesos2")
foreach(case sigterm newton-failure)
  ddc_add_restart_test(restart_${case}_monolithic_np1 1 ${case} ${DDC_HALF_RINGS} REFERENCE monolithic_np1
    ARGS ${DDC_RESTART_CONVENTIONAL})
  ddc_add_restart_test(restart_${case}_monolithic_np2 2 ${case} ${DDC_HALF_RINGS} REFERENCE monolithic_np2
    ARGS ${DDC_RESTART_CONVENTIONAL} --set "Solver/Linear Solver/Type=Amesos2")
endforeach()
# Stopped from outside once the run is past step 20 of 100 (the step it
# stops at is not known in advance): the uninterrupted run is
# half_rings_decomposed_100 (suites/studies.cmake), the same deck and options.
foreach(case kill usr1-to-mpirun)
  ddc_add_restart_test(restart_${case}_feti_np2 2 ${case} ${DDC_HALF_RINGS}
    ENVIRONMENT REFERENCE_RUN=${DDC_RUNS}/half_rings_decomposed_100 FIXTURES half_rings_decomposed_100
    ARGS ${DDC_HALF_RINGS_100})
endforeach()
# Restarted on another rank count (history to 1e-10: the uninterrupted run
# with Exodus output is the same computation).
ddc_add_restart_test(restart_other_ranks_feti_np2_to_1 2 other-ranks:1 ${DDC_HALF_RINGS} REFERENCE feti_np2)
ddc_add_restart_test(restart_other_ranks_feti_np1_to_3 1 other-ranks:3 ${DDC_HALF_RINGS} REFERENCE feti_np1
  PROCESSORS 2)
ddc_add_restart_test(restart_other_ranks_monolithic_np2_to_1 2 other-ranks:1 ${DDC_HALF_RINGS}
  ARGS ${DDC_RESTART_CONVENTIONAL})
# Dynamics (velocities and accelerations in the checkpoint) and Step Control
# (the adaptive controller's state).
ddc_add_restart_test(restart_sigterm_dynamics_np2 2 sigterm ${PROJECT_SOURCE_DIR}/examples/bar_impact.xml)
# A checkpoint written on parts of the mesh continues with the whole mesh and
# the other way round, on another rank count (dynamics, no contact).
ddc_add_restart_test(restart_other_mode_np2_to_3 2 other-mode:3 ${PROJECT_SOURCE_DIR}/examples/bar_vibration.xml)
# With PT-Scotch the parts are built in ranges of elements (no rank holds
# the whole mesh): its checkpoint continues with the whole mesh, and the
# other way round.
# Its Exodus II results, one file or one piece per rank, continue across
# the layouts; and a run on parts stopped and restarted in place ends with
# the uninterrupted run's pieces, byte for byte (Amesos2: with MUMPS two
# uninterrupted runs on 2 ranks already differ in the last bits, above).
ddc_add_restart_test(restart_other_mode_in_ranges_np2_to_3 2 other-mode:3
  ${PROJECT_SOURCE_DIR}/examples/bar_vibration.xml ENVIRONMENT PYTHON=${DDC_SYSTEM_PYTHON}
  ARGS --set "Partition/Method=PT-Scotch" --set "Output/Exodus=true")
# With contact (the half rings, the decomposed element under FETI-DP): the
# slots name their slave nodes and master facets by ids in the whole mesh,
# so a checkpoint of either layout continues in the other (the history;
# PT-Scotch cuts 3 ranks' parts differently from 2, so FETI-DP's answers
# differ at its solver tolerance, 1e-11 in the energy, and the stresses of
# the unloaded rings at the last steps, round-off of 1e-11, differ
# relatively: the Exodus II copy across layouts is the case above).
ddc_add_restart_test(restart_other_mode_contact_in_ranges_np2_to_3 2 other-mode:3 ${DDC_HALF_RINGS}
  LABELS contact ARGS --set "Partition/Method=PT-Scotch")
# The same with the half rings read from an Exodus II file (output.cmake):
# on parts each rank read its slab of the file.
ddc_add_restart_test(restart_other_mode_exodus_in_ranges_np2_to_3 2 other-mode:3 ${DDC_RUNS}/exodus_mesh/half_rings.xml
  LABELS contact output FIXTURES exodus_mesh_half_rings_files ARGS --set "Partition/Method=PT-Scotch")
ddc_add_restart_test(restart_sigterm_in_ranges_np2 2 sigterm ${PROJECT_SOURCE_DIR}/examples/bar_vibration.xml
  ARGS --set "Partition/Method=PT-Scotch" --set "Partition/Mesh On Every Rank=false" --set "Output/Exodus=true"
    --set "Solver/Linear Solver/Type=Amesos2")
ddc_add_restart_test(restart_sigterm_step_control_np2 2 sigterm
  ${PROJECT_SOURCE_DIR}/examples/two_half_rings_adaptive.xml)
# Coulomb friction (the slots' stick/slip states, tangential bases and
# multipliers in the checkpoint; the slip measured from the step start):
# the Cattaneo cylinder stopped during the push, the conventional element
# solved monolithically on 1 rank (history equal field for field), and the
# decomposed element under FETI-DP (the slide variant, Box Grid 2 x 2)
# stopped on 2 ranks and continued on 1 (to 1e-10).
set(DDC_CATTANEO ${PROJECT_SOURCE_DIR}/examples/cattaneo_2d.xml)
ddc_add_restart_test(restart_sigterm_friction_monolithic_np1 1 sigterm ${DDC_CATTANEO} LABELS contact)
ddc_add_restart_test(restart_other_ranks_friction_feti_np2_to_1 2 other-ranks:1 ${DDC_CATTANEO} LABELS contact
  ARGS --set "Contact/Formulation=Decomposed Node-To-Surface" --set "Boundary Conditions/Push/Type=Displacement"
    --set "Boundary Conditions/Push/Components=X" --set "Boundary Conditions/Push/Value X=0.0025"
    --set "Boundary Conditions/Push/Traction X=0" --set "Solver/Strategy=FETI-DP"
    --set "Solver/FETI-DP/Belos/Convergence Tolerance=1e-12" --set "Partition/Method=Box Grid")
# A failed run whose checkpoint cannot be written reports both.
ddc_add_restart_test(restart_unwritable_np2 2 unwritable ${DDC_HALF_RINGS} LABELS negative)
# A finished run taken further (a larger final load factor).
ddc_add_restart_test(restart_extend_np2 2 extend ${DDC_HALF_RINGS})
foreach(np 1 2)
  foreach(case corrupted deck-change no-checkpoint)
    ddc_add_restart_test(restart_${case}_np${np} ${np} ${case} ${DDC_HALF_RINGS} LABELS negative)
  endforeach()
endforeach()
# What a restart and a new run refuse, on a block read from a Gmsh file
# (inputs/restart_block.xml, 16 elements; tools/restart_cases.sh, the cases
# after `reference`): a mesh or element-map file changed since the run read
# it (Gmsh also on 3 ranks), a final load factor below the checkpoint's, the
# checkpoint of the finished run when the stopped one left none, a plain run
# into a stopped run's directory, an earlier result edited by hand, --restart
# naming the staging directory or the checkpoint file, and a checkpoint that
# is a directory, a device or too large for memory; the messages of Exodus II
# output switched on at a restart and of a full disk while writing
# results.e. Each leaves the directories it names unchanged.
if(NOT DDC_SYSTEM_PYTHON)
  find_program(DDC_SYSTEM_PYTHON python3 PATHS /usr/bin NO_DEFAULT_PATH)
endif()
set(DDC_RESTART_BLOCK ${DDC_INPUTS}/restart_block.xml)
foreach(np 1 2)
  foreach(case input-change:gmsh input-change:map input-change:exodus final-below finished-checkpoint rerun-stopped
          edited-result wrong-source bad-checkpoint exodus-messages)
    string(REGEX REPLACE "[-:]" "_" name "${case}")
    ddc_add_restart_test(restart_${name}_np${np} ${np} ${case} ${DDC_RESTART_BLOCK} LABELS negative
      ENVIRONMENT PYTHON=${DDC_SYSTEM_PYTHON})
  endforeach()
endforeach()
# The Exodus II messages on parts of the mesh, where each rank writes its piece.
ddc_add_restart_test(restart_exodus_messages_parts_np2 2 exodus-messages ${DDC_RESTART_BLOCK} LABELS negative
  ENVIRONMENT PYTHON=${DDC_SYSTEM_PYTHON} ARGS --set "Partition/Mesh On Every Rank=false")
ddc_add_restart_test(restart_input_change_gmsh_np3 3 input-change:gmsh ${DDC_RESTART_BLOCK} PROCESSORS 2
  LABELS negative)
