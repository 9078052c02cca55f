# Solver/Strategy = FETI-DP against Monolithic (MUMPS) on the same partition
# (the DOF numbering depends on the partition, so both runs number alike).
# Belos to 1e-12 so that both Newton loops take the same iterations.

# ddc_feti_vs_monolithic(<example> [CHECKS c...] [FETI_ARGS a...]):
# examples/<example>.xml with 8 METIS subdomains under FETI-DP (Belos to
# 1e-12) and Monolithic MUMPS on 1 and 2 ranks (runs
# feti_<example>_<strategy>_np<np>; several subdomains per rank), compared by
# feti_vs_monolithic_<example>_np<np> (strain energy, Newton iterations and
# external work to 1e-8); CHECKS (cmake/CheckHistory.cmake) on the FETI-DP
# history in feti_<example>_iterations_np<np>; FETI_ARGS: more options of the
# FETI-DP runs.
function(ddc_feti_vs_monolithic ex)
  cmake_parse_arguments(F "" "" "CHECKS;FETI_ARGS" ${ARGN})
  foreach(np 1 2)
    foreach(strategy FETI-DP Monolithic)
      set(name feti_${ex}_${strategy}_np${np})
      set(args ${PROJECT_SOURCE_DIR}/examples/${ex}.xml --set "Solver/Strategy=${strategy}"
        --set "Partition/Number of Subdomains=8" --set "Output/VTK=false" --output-dir ${DDC_RUNS}/${name})
      if(strategy STREQUAL "FETI-DP")
        list(APPEND args --set "Solver/FETI-DP/Belos/Convergence Tolerance=1e-12" ${F_FETI_ARGS})
      endif()
      ddc_add_run_test(${name} RANKS ${np} FIXTURE ARGS ${args} FILES ${DDC_RUNS}/${name}/history.csv LABELS feti
        REGEX "step +1/1 +load 1 +Newton +2")
    endforeach()
    ddc_compare_histories(feti_vs_monolithic_${ex}_np${np} feti_${ex}_FETI-DP_np${np} feti_${ex}_Monolithic_np${np}
      1e-8 COLUMNS strain_energy newton_iterations external_work LABELS feti)
    if(F_CHECKS)
      ddc_check_history(feti_${ex}_iterations_np${np} feti_${ex}_FETI-DP_np${np} CHECKS ${F_CHECKS} LABELS feti)
    endif()
  endforeach()
endfunction()

# examples/elastic_block.xml; FETI-DP itself does not depend on the number of
# ranks (iterative: to the Belos tolerance, not to round-off, hence 1e-8).
ddc_feti_vs_monolithic(elastic_block)
ddc_compare_histories(feti_rank_independence_elastic_block feti_elastic_block_FETI-DP_np1
  feti_elastic_block_FETI-DP_np2 1e-8 COLUMNS strain_energy newton_iterations external_work LABELS feti)

# A subdomain the corner rule leaves floating (an island, inputs/feti_island.map):
# two of its interface nodes are made primal (rule 3 of selectPrimalNodes); the
# progress line reports it, and the result equals the Monolithic one.
foreach(np 1 2)
  foreach(strategy FETI-DP Monolithic)
    set(name feti_island_${strategy}_np${np})
    set(args ${DDC_INPUTS}/feti_island.xml --set "Solver/Strategy=${strategy}" --output-dir ${DDC_RUNS}/${name})
    set(regex "step +1/1 +load 1 +Newton +2")
    if(strategy STREQUAL "FETI-DP")
      list(APPEND args --set "Solver/FETI-DP/Belos/Convergence Tolerance=1e-12")
      set(regex "FETI-DP: subdomain 1: 2 interface node\\(s\\) made primal.*${regex}")
    endif()
    ddc_add_run_test(${name} RANKS ${np} FIXTURE ARGS ${args} FILES ${DDC_RUNS}/${name}/history.csv LABELS feti
      REGEX "${regex}")
  endforeach()
  ddc_compare_histories(feti_vs_monolithic_island_np${np} feti_island_FETI-DP_np${np} feti_island_Monolithic_np${np}
    1e-8 COLUMNS strain_energy newton_iterations external_work LABELS feti)
endforeach()

# FETI-DP in 3-D: examples/block_3d.xml with 8 METIS subdomains equals the
# monolithic MUMPS solution (Belos to 1e-12, so both Newton loops take the
# same iterations) on 1 and 2 ranks, and the dual iterations of the step stay
# within the baseline measured with vertices only (doc/feti-dp.md "In 3-D"):
# a regression in the primal selection or the preconditioner shows as more
# iterations. The bound was set for the strong coarse spaces (every edge node
# primal, or face averages): the run uses the faces. The default (edge ends
# and edge averages, cheaper on large meshes) takes 60 iterations on this
# 1275-DOF slab-like partition; its bounds are in feti_default_3d_* below.
ddc_feti_vs_monolithic(block_3d CHECKS "last:dual_iterations:<=:40"
  FETI_ARGS --set "Solver/FETI-DP/Primal Constraints=Vertices, Edges and Faces")
# The FETI-DP defaults in 3-D (doc/performance.md, "FETI-DP levers"): edge
# ends and edge averages as the coarse space, Eisenstat-Walker forcing terms,
# one factorisation. block_3d at Refinement 3 (24,843 DOFs), 32 METIS
# subdomains, 2 ranks, one linear step = 2 Newton solves. Measured: 28 dual
# iterations in the first solve and 8 in the one that confirms convergence
# (36 in the step; 57 with Forcing Term = Constant, where the second solve
# costs as much as the first). The step must stay within 42, and the result
# must equal the Constant run's (strain energy and work to 1e-8: the forcing
# terms change the cost, not the converged solution).
foreach(ft Eisenstat-Walker Constant)
  ddc_add_run_test(feti_default_3d_${ft} RANKS 2 FIXTURE
    ARGS ${PROJECT_SOURCE_DIR}/examples/block_3d.xml --set "Mesh/Bodies/Block/Box/Refinement=3"
      --set "Solver/Strategy=FETI-DP" --set "Partition/Number of Subdomains=32" --set "Newton/Forcing Term=${ft}"
      --set "Output/VTK=false" --output-dir ${DDC_RUNS}/feti_default_3d_${ft}
    FILES ${DDC_RUNS}/feti_default_3d_${ft}/history.csv LABELS feti REGEX "step +1/1 +load 1 +Newton +2")
endforeach()
ddc_check_history(feti_default_3d_iterations feti_default_3d_Eisenstat-Walker CHECKS "last:dual_iterations:<=:42"
  LABELS feti)
ddc_compare_histories(feti_default_3d_forcing_same_result feti_default_3d_Eisenstat-Walker feti_default_3d_Constant
  1e-8 COLUMNS strain_energy external_work newton_iterations LABELS feti)
# FETI-DP on parts of the mesh ('Partition/Mesh On Every Rank' = false: each
# rank selects the primal nodes of its subdomains with the holders of their
# nodes, doc/feti-dp.md "Primal nodes"): the same run as on the whole mesh,
# to round-off, with edge ends and shared faces (32 subdomains), with every
# subdomain-edge node (512) and with a subdomain that rule 3 anchors (the
# island: its report line comes from the rank that decides it).
function(ddc_feti_on_parts whole deck)
  cmake_parse_arguments(P "" "REGEX" "ARGS" ${ARGN})
  ddc_add_run_test(feti_on_parts_${whole} RANKS 2 FIXTURE
    ARGS ${deck} --set "Solver/Strategy=FETI-DP" ${P_ARGS} --set "Output/VTK=false"
      --set "Partition/Mesh On Every Rank=false" --output-dir ${DDC_RUNS}/feti_on_parts_${whole}
    FILES ${DDC_RUNS}/feti_on_parts_${whole}/history.csv LABELS feti REGEX "${P_REGEX}")
  ddc_compare_histories(feti_on_parts_equal_whole_${whole} ${whole} feti_on_parts_${whole} 1e-12 LABELS feti)
endfunction()
ddc_feti_on_parts(feti_default_3d_Eisenstat-Walker ${PROJECT_SOURCE_DIR}/examples/block_3d.xml
  ARGS --set "Mesh/Bodies/Block/Box/Refinement=3" --set "Partition/Number of Subdomains=32" REGEX "step +1/1")
ddc_feti_on_parts(feti_primal_Automatic_512_subdomains ${PROJECT_SOURCE_DIR}/examples/block_3d.xml
  ARGS --set "Mesh/Bodies/Block/Box/Refinement=2" --set "Partition/Number of Subdomains=512"
    --set "Solver/FETI-DP/Method=FETI-DP"
  REGEX "no edge averages.*step +1/1")
ddc_feti_on_parts(feti_island_FETI-DP_np2 ${DDC_INPUTS}/feti_island.xml
  ARGS --set "Solver/FETI-DP/Belos/Convergence Tolerance=1e-12"
  REGEX "FETI-DP: subdomain 1: 2 interface node\\(s\\) made primal.*step +1/1")
# FETI-DP on a mesh no rank holds whole (PT-Scotch, Mesh On Every Rank =
# false: the bodies generated in ranges of elements): the whole-mesh
# PT-Scotch run with the same partition, to round-off.
foreach(mode whole ranges)
  if(mode STREQUAL "ranges")
    set(on_every_rank false)
  else()
    set(on_every_rank true)
  endif()
  ddc_add_run_test(feti_ptscotch_${mode}_block_3d RANKS 2 FIXTURE
    ARGS ${PROJECT_SOURCE_DIR}/examples/block_3d.xml --set "Solver/Strategy=FETI-DP"
      --set "Mesh/Bodies/Block/Box/Refinement=3" --set "Partition/Number of Subdomains=32"
      --set "Partition/Method=PT-Scotch" --set "Partition/Mesh On Every Rank=${on_every_rank}" --set "Output/VTK=false"
      --output-dir ${DDC_RUNS}/feti_ptscotch_${mode}_block_3d
    FILES ${DDC_RUNS}/feti_ptscotch_${mode}_block_3d/history.csv LABELS feti REGEX "step +1/1")
endforeach()
ddc_compare_histories(feti_mesh_in_ranges_equal_whole feti_ptscotch_whole_block_3d feti_ptscotch_ranges_block_3d 1e-12
  LABELS feti)

# A FETI-DP run reports the size of its coarse problem (doc/feti-dp.md "In 3-D").
ddc_add_run_test(feti_reports_coarse_size RANKS 1
  ARGS ${PROJECT_SOURCE_DIR}/examples/block_3d.xml --set "Solver/Strategy=FETI-DP"
    --set "Partition/Number of Subdomains=8" --set "Output/VTK=false" --output-dir ${DDC_RUNS}/feti_reports_coarse_size
  REGEX "FETI-DP: 8 subdomains, [1-9][0-9]* primal nodes, coarse problem of [1-9][0-9]* DOFs" LABELS feti)
# 'Primal Constraints' = Automatic in 3-D (doc/feti-dp.md "In 3-D"): edge
# averages below 512 subdomains, every subdomain-edge node primal and no
# averages from 512 on, which is then the same run as 'Primal Constraints' =
# Vertices; an explicit choice is kept (block_3d at Refinement 2, 2048
# elements; at Refinement 3 for the explicit edges, which on 4-element
# subdomains find no edge with an interior node to average).
set(averages_off "Primal Constraints = Automatic, on 512 subdomains in 3-D: every subdomain-edge node primal, no \
edge averages")
# FETI-DP's rule, so 'Method' = FETI-DP where Automatic would choose BDDC
# (below); below 512 subdomains, and with edges, which BDDC cannot take,
# Automatic stays FETI-DP.
foreach(c "511;Automatic;Automatic;[1-9][0-9]*;2;Automatic" "512;Automatic;Automatic;0;2;FETI-DP"
          "512;Vertices;Vertices;0;2;FETI-DP" "512;Edges;Vertices and Edges;[1-9][0-9]*;3;Automatic")
  list(GET c 0 count)
  list(GET c 1 tag)
  list(GET c 2 primal)
  list(GET c 3 averages)
  list(GET c 4 refinement)
  list(GET c 5 method)
  set(regex "FETI-DP: ${count} subdomains, [1-9][0-9]* primal nodes, coarse problem of [1-9][0-9]* DOFs \\([0-9]+ at \
primal nodes, ${averages} edge/face constraints\\)")
  if(count EQUAL 512 AND tag STREQUAL "Automatic")
    set(regex "${averages_off}.*${regex}")
  endif()
  ddc_add_run_test(feti_primal_${tag}_${count}_subdomains RANKS 2 FIXTURE
    ARGS ${PROJECT_SOURCE_DIR}/examples/block_3d.xml --set "Mesh/Bodies/Block/Box/Refinement=${refinement}"
      --set "Solver/Strategy=FETI-DP" --set "Partition/Number of Subdomains=${count}"
      --set "Solver/FETI-DP/Primal Constraints=${primal}" --set "Solver/FETI-DP/Method=${method}"
      --set "Output/VTK=false" --output-dir ${DDC_RUNS}/feti_primal_${tag}_${count}_subdomains
    FILES ${DDC_RUNS}/feti_primal_${tag}_${count}_subdomains/history.csv
    REGEX "${regex}" LABELS feti)
endforeach()
ddc_compare_histories(feti_primal_automatic_is_vertices_from_512 feti_primal_Automatic_512_subdomains
  feti_primal_Vertices_512_subdomains 1e-14 LABELS feti)
# 'Method' = Automatic from 512 subdomains in 3-D without contact is BDDC
# (doc/feti-dp.md "BDDC"), with FETI-DP's answer to the Krylov tolerance
# (kMethodsAgree, Belos' default 1e-10; measured 1.2e-13 in the strain
# energy).
set(kMethodsAgree 1e-10)
ddc_add_run_test(feti_method_automatic_512_subdomains RANKS 2 FIXTURE
  ARGS ${PROJECT_SOURCE_DIR}/examples/block_3d.xml --set "Mesh/Bodies/Block/Box/Refinement=2"
    --set "Solver/Strategy=FETI-DP" --set "Partition/Number of Subdomains=512" --set "Output/VTK=false"
    --output-dir ${DDC_RUNS}/feti_method_automatic_512_subdomains
  FILES ${DDC_RUNS}/feti_method_automatic_512_subdomains/history.csv
  REGEX "Method = Automatic, on 512 subdomains in 3-D without contact: BDDC.*BDDC: 512 subdomains, [1-9][0-9]* \
primal nodes, coarse problem of [1-9][0-9]* DOFs" LABELS feti)
ddc_feti_on_parts(feti_method_automatic_512_subdomains ${PROJECT_SOURCE_DIR}/examples/block_3d.xml
  ARGS --set "Mesh/Bodies/Block/Box/Refinement=2" --set "Partition/Number of Subdomains=512"
  REGEX "BDDC: 512 subdomains.*step +1/1")
ddc_compare_histories(feti_method_automatic_bddc_equals_feti_dp feti_method_automatic_512_subdomains
  feti_primal_Vertices_512_subdomains ${kMethodsAgree} COLUMNS strain_energy external_work load_factor LABELS feti)
# The automatic subdomain count ('Partition/Number of Subdomains' = 0,
# doc/performance.md): block_3d at Refinement 2 has 2673 nodes (8019 DOFs
# before the clamp), so about one subdomain per 1650 DOFs is 5 on 2 ranks;
# 'Subdomain Size' = 4000 gives 2; Monolithic keeps one per rank.
foreach(c "5;0;FETI-DP" "2;4000;FETI-DP" "2;0;Monolithic")
  list(GET c 0 count)
  list(GET c 1 size)
  list(GET c 2 strategy)
  ddc_add_run_test(automatic_subdomain_count_${strategy}_${size} RANKS 2
    ARGS ${PROJECT_SOURCE_DIR}/examples/block_3d.xml --set "Mesh/Bodies/Block/Box/Refinement=2"
      --set "Solver/Strategy=${strategy}" --set "Partition/Subdomain Size=${size}" --set "Output/VTK=false"
      --output-dir ${DDC_RUNS}/automatic_subdomain_count_${strategy}_${size}
    REGEX "DOFs, ${count} subdomains on 2 ranks" LABELS feti)
endforeach()
