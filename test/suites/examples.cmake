# The shipped examples (examples/*.xml) double as smoke tests: each runs to
# the end and writes its history and VTK series. Their results do not depend
# on the number of ranks (summation order only: 1e-10; FETI-DP is iterative:
# to its tolerance).
# (The main example, examples/two_half_rings.sh, is in suites/studies.cmake.)
foreach(ex arch elastic_block bar_vibration)
  foreach(np 1 2)
    ddc_add_run_test(example_${ex}_np${np} RANKS ${np} FIXTURE
      ARGS ${PROJECT_SOURCE_DIR}/examples/${ex}.xml --output-dir ${DDC_RUNS}/example_${ex}_np${np}
      FILES ${DDC_RUNS}/example_${ex}_np${np}/history.csv ${DDC_RUNS}/example_${ex}_np${np}/vtk/solution.pvd
      LABELS example)
  endforeach()
  ddc_compare_histories(rank_independence_${ex} example_${ex}_np1 example_${ex}_np2 1e-10)
endforeach()

# 3-D: examples/block_3d.xml (Hex8, linear elastic) and
# examples/half_ring_arch_3d.xml (Hex8, neo-Hookean, large deformation) on 1,
# 2 and 3 ranks: the same history to 1e-10 (doc/verification.md "3-D analysis").
foreach(ex block_3d half_ring_arch_3d)
  foreach(np 1 2 3)
    set(name example_${ex}_np${np})
    ddc_add_run_test(${name} RANKS ${np} FIXTURE
      ARGS ${PROJECT_SOURCE_DIR}/examples/${ex}.xml --output-dir ${DDC_RUNS}/${name}
      FILES ${DDC_RUNS}/${name}/history.csv ${DDC_RUNS}/${name}/vtk/solution.pvd LABELS example)
  endforeach()
  foreach(np 2 3)
    ddc_compare_histories(rank_independence_${ex}_np${np} example_${ex}_np1 example_${ex}_np${np} 1e-10)
  endforeach()
endforeach()

# The distribution line (doc/user-guide.md "The distribution line"): with
# METIS, one subdomain per rank, the busiest of P ranks assembles and owns at
# most 1/P + 10 % of block_3d's 256 elements and 425 nodes (2 ranks: below
# 60 %, 4 ranks: below 35 %).
set(DISTRIBUTION_SHARE_np2 "5[0-9]\\.[0-9] %")
set(DISTRIBUTION_SHARE_np4 "(2[5-9]|3[0-4])\\.[0-9] %")
foreach(np 2 4)
  ddc_add_run_test(distribution_line_block_3d_np${np} RANKS ${np}
    ARGS ${PROJECT_SOURCE_DIR}/examples/block_3d.xml --set "Output/VTK=false"
      --output-dir ${DDC_RUNS}/distribution_line_block_3d_np${np}
    LABELS example
    REGEX "distribution: the busiest rank assembles [0-9]+ of 256 elements \\(${DISTRIBUTION_SHARE_np${np}}\\), owns [0-9]+ of 425 nodes \\(${DISTRIBUTION_SHARE_np${np}}\\)")
endforeach()

# Partition/Mesh On Every Rank = false: each rank keeps only its part of the
# mesh. The busiest rank holds at most 1/P + 10 % of the elements, and owns
# at most that of the nodes (the nodes beyond its halo); the run is the
# whole-mesh run on as many ranks (same partition), to round-off.
foreach(np 2 4)
  ddc_add_run_test(distribution_line_block_3d_parts_np${np} RANKS ${np} FIXTURE
    ARGS ${PROJECT_SOURCE_DIR}/examples/block_3d.xml --set "Partition/Mesh On Every Rank=false"
      --output-dir ${DDC_RUNS}/distribution_line_block_3d_parts_np${np}
    FILES ${DDC_RUNS}/distribution_line_block_3d_parts_np${np}/history.csv
    LABELS example
    REGEX "owns [0-9]+ of 425 nodes \\(${DISTRIBUTION_SHARE_np${np}}\\); the busiest rank holds [0-9]+ of 256 elements \\(${DISTRIBUTION_SHARE_np${np}}\\) and [0-9]+ of 425 nodes")
endforeach()
ddc_compare_histories(parts_equal_whole_block_3d_np2 example_block_3d_np2 distribution_line_block_3d_parts_np2 1e-12)

# With Partition/Method = PT-Scotch as well, no rank builds the whole mesh:
# each generates an even range of the elements, PT-Scotch partitions them in
# parallel and each element moves to the rank of its subdomain. The busiest
# rank holds at most 1/P + 10 % of the elements and owns that of the nodes;
# the run is the whole-mesh PT-Scotch run on as many ranks (the same
# partition) to round-off, and on 4 ranks the 1-rank run to the examples'
# rank-independence tolerance; the 2-D elastic block likewise on 3 ranks.
# The block_3d runs write Exodus II results, one file with the whole mesh
# and one piece per rank on parts (compared in output.cmake).
set(IN_RANGES --set "Partition/Method=PT-Scotch" --set "Partition/Mesh On Every Rank=false" --set "Output/VTK=false")
ddc_add_run_test(ptscotch_whole_block_3d_np2 RANKS 2 FIXTURE
  ARGS ${PROJECT_SOURCE_DIR}/examples/block_3d.xml --set "Partition/Method=PT-Scotch" --set "Output/VTK=false"
    --set "Output/Exodus=true"
    --output-dir ${DDC_RUNS}/ptscotch_whole_block_3d_np2
  FILES ${DDC_RUNS}/ptscotch_whole_block_3d_np2/history.csv LABELS example REGEX "every rank holds the whole mesh")
foreach(np 2 4)
  ddc_add_run_test(mesh_in_ranges_block_3d_np${np} RANKS ${np} FIXTURE
    ARGS ${PROJECT_SOURCE_DIR}/examples/block_3d.xml ${IN_RANGES} --set "Output/Exodus=true"
      --output-dir ${DDC_RUNS}/mesh_in_ranges_block_3d_np${np}
    FILES ${DDC_RUNS}/mesh_in_ranges_block_3d_np${np}/history.csv
    LABELS example
    REGEX "owns [0-9]+ of 425 nodes \\(${DISTRIBUTION_SHARE_np${np}}\\); the busiest rank holds [0-9]+ of 256 elements \\(${DISTRIBUTION_SHARE_np${np}}\\) and [0-9]+ of 425 nodes [^;]*; no rank held the whole mesh \\(built in ranges of elements\\)")
endforeach()
ddc_compare_histories(mesh_in_ranges_equal_whole_block_3d_np2 ptscotch_whole_block_3d_np2 mesh_in_ranges_block_3d_np2 1e-12)
ddc_compare_histories(mesh_in_ranges_rank_independence_block_3d_np4 example_block_3d_np1 mesh_in_ranges_block_3d_np4 1e-10)
ddc_add_run_test(mesh_in_ranges_elastic_block_np3 RANKS 3 FIXTURE
  ARGS ${PROJECT_SOURCE_DIR}/examples/elastic_block.xml ${IN_RANGES}
    --output-dir ${DDC_RUNS}/mesh_in_ranges_elastic_block_np3
  FILES ${DDC_RUNS}/mesh_in_ranges_elastic_block_np3/history.csv LABELS example
  REGEX "no rank held the whole mesh \\(built in ranges of elements\\)")
ddc_compare_histories(mesh_in_ranges_rank_independence_elastic_block example_elastic_block_np1
  mesh_in_ranges_elastic_block_np3 1e-10)
# The other generators too (the arch's annular sector, the 3-D arch's
# cylindrical shell sector): the 1-rank runs to the rank-independence
# tolerance. A Gmsh file each rank reads its even range of elements of (as
# the file streams by): the whole-mesh PT-Scotch run on as many ranks (the
# same partition), its Exodus II pieces too (output.cmake).
ddc_add_run_test(mesh_in_ranges_arch_np3 RANKS 3 FIXTURE
  ARGS ${PROJECT_SOURCE_DIR}/examples/arch.xml ${IN_RANGES} --output-dir ${DDC_RUNS}/mesh_in_ranges_arch_np3
  FILES ${DDC_RUNS}/mesh_in_ranges_arch_np3/history.csv LABELS example
  REGEX "; no rank held the whole mesh \\(built in ranges of elements\\)")
ddc_compare_histories(mesh_in_ranges_rank_independence_arch example_arch_np1 mesh_in_ranges_arch_np3 1e-10)
ddc_add_run_test(mesh_in_ranges_half_ring_arch_3d_np3 RANKS 3 FIXTURE
  ARGS ${PROJECT_SOURCE_DIR}/examples/half_ring_arch_3d.xml ${IN_RANGES}
    --output-dir ${DDC_RUNS}/mesh_in_ranges_half_ring_arch_3d_np3
  FILES ${DDC_RUNS}/mesh_in_ranges_half_ring_arch_3d_np3/history.csv LABELS example
  REGEX "; no rank held the whole mesh \\(built in ranges of elements\\)")
ddc_compare_histories(mesh_in_ranges_rank_independence_half_ring_arch_3d example_half_ring_arch_3d_np1
  mesh_in_ranges_half_ring_arch_3d_np3 1e-10)
foreach(mode whole in_ranges)
  ddc_mesh_mode(${mode} parts said)
  ddc_add_run_test(gmsh_block_${mode}_np3 RANKS 3 FIXTURE
    ARGS ${DDC_INPUTS}/restart_block.xml --set "Partition/Method=PT-Scotch" --set "Output/VTK=false"
      --set "Output/Exodus=true" ${parts} --output-dir ${DDC_RUNS}/gmsh_block_${mode}_np3
    FILES ${DDC_RUNS}/gmsh_block_${mode}_np3/history.csv LABELS example REGEX "${said}")
endforeach()
ddc_compare_histories(gmsh_block_in_ranges_equal_whole gmsh_block_whole_np3 gmsh_block_in_ranges_np3 1e-12)

# The bar impact (implicit dynamics with contact, the decomposed element
# under FETI-DP): on 1, 2 and 3 ranks, each subdomain factorised once
# (linear material, constant time step: the contact changes only constraint
# rows), the same history on every rank count (FETI-DP is iterative: to
# its tolerance, not to round-off, and the dual iterations may differ by
# one; the y and z forces are round-off).
foreach(np 1 2 3)
  ddc_add_run_test(example_bar_impact_np${np} RANKS ${np} FIXTURE
    ARGS ${PROJECT_SOURCE_DIR}/examples/bar_impact.xml --output-dir ${DDC_RUNS}/example_bar_impact_np${np}
    FILES ${DDC_RUNS}/example_bar_impact_np${np}/history.csv ${DDC_RUNS}/example_bar_impact_np${np}/vtk/solution.pvd
    LABELS example contact feti dynamics
    REGEX "step +96/96 .*contacts 0.*each subdomain factorised 1 time")
endforeach()
foreach(np 2 3)
  ddc_compare_histories(rank_independence_bar_impact_np${np} example_bar_impact_np1 example_bar_impact_np${np} 1e-8
    COLUMNS strain_energy newton_iterations active_contacts contact_force_x contact_exchanges kinetic_energy
      total_energy)
endforeach()

# The two half-rings with mass (the decomposed element, FETI-DP, 100 time
# steps): contact starts and ends, one exchange per step.
ddc_add_run_test(example_two_half_rings_dynamic RANKS 2
  ARGS ${PROJECT_SOURCE_DIR}/examples/two_half_rings_dynamic.xml --set "Output/VTK=false"
    --output-dir ${DDC_RUNS}/example_two_half_rings_dynamic
  FILES ${DDC_RUNS}/example_two_half_rings_dynamic/history.csv LABELS example contact feti dynamics
  REGEX "step +50/100 .*contacts [1-9].*step 100/100 .*contacts 0.*102 contact-geometry exchanges")
# The same with Step Control: in dynamics a step above the tolerance is
# repeated with its end's geometry at the same time step (no new
# factorisation for that), and the run reaches the final time.
ddc_add_run_test(example_two_half_rings_dynamic_step_control RANKS 2
  ARGS ${PROJECT_SOURCE_DIR}/examples/two_half_rings_dynamic.xml --set "Output/VTK=false"
    --set "Step Control/Error Tolerance=0.005" --output-dir ${DDC_RUNS}/example_two_half_rings_dynamic_step_control
  FILES ${DDC_RUNS}/example_two_half_rings_dynamic_step_control/history.csv LABELS example contact feti dynamics
  REGEX "repeating it with the projections and normals of its end.*step +[0-9]+  time 5 .*contacts 0")

# Step control by the frozen-geometry error (doc/contact.md "Step control by
# the frozen-geometry error", doc/figure4.md "Step control"):
# examples/two_half_rings_adaptive.xml on 1, 2 and 3 ranks: the controller
# decides the same on every rank count (the same steps, the same repeats and
# reductions); FETI-DP is iterative, so the sizes, which the indicator sets,
# agree to 1e-6, not to round-off. (The 2-rank run is also the tol-0.005 run
# of the step-control study, suites/studies.cmake.)
foreach(np 1 2 3)
  ddc_add_run_test(example_two_half_rings_adaptive_np${np} RANKS ${np} FIXTURE
    ARGS ${PROJECT_SOURCE_DIR}/examples/two_half_rings_adaptive.xml --set "Output/VTK=false"
      --output-dir ${DDC_RUNS}/example_two_half_rings_adaptive_np${np}
    FILES ${DDC_RUNS}/example_two_half_rings_adaptive_np${np}/history.csv LABELS example contact feti dd_contact
    REGEX "step +20  load 1 .*size 0.05.*contacts 0")
endforeach()
foreach(np 2 3)
  ddc_compare_histories(rank_independence_two_half_rings_adaptive_np${np} example_two_half_rings_adaptive_np1
    example_two_half_rings_adaptive_np${np} 1e-6
    COLUMNS step load_factor step_size rejected_steps geometry_corrections contact_exchanges strain_energy)
endforeach()
