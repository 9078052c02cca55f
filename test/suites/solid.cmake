# Continuum analysis without contact beyond the examples (suites/examples.cmake).

# Plane-strain consistency: the 2-D arch (examples/arch.xml, Quad4: the run
# example_arch_np2) and the same arch extruded one element through a depth
# of 1 with u_z = 0 on both faces (inputs/arch_extruded.xml) have the same
# strain energy and external work in every step (per unit depth) and take
# the same Newton iterations: Hex8 against Quad4, Hex27 against Quad9, to 1e-10.
ddc_add_run_test(plane_strain_arch_Quad9 RANKS 2 FIXTURE
  ARGS ${PROJECT_SOURCE_DIR}/examples/arch.xml --set "Mesh/Bodies/Arch/Element/Type=Quad9"
    --set "Output/VTK=false" --output-dir ${DDC_RUNS}/plane_strain_arch_Quad9
  FILES ${DDC_RUNS}/plane_strain_arch_Quad9/history.csv)
foreach(pair "example_arch_np2;Quad4;Hex8" "plane_strain_arch_Quad9;Quad9;Hex27")
  list(GET pair 0 quad_run)
  list(GET pair 1 quad)
  list(GET pair 2 hex)
  ddc_add_run_test(plane_strain_arch_${hex} RANKS 2 FIXTURE
    ARGS ${DDC_INPUTS}/arch_extruded.xml --set "Mesh/Bodies/Arch/Element/Type=${hex}"
      --set "Output/VTK=false" --output-dir ${DDC_RUNS}/plane_strain_arch_${hex}
    FILES ${DDC_RUNS}/plane_strain_arch_${hex}/history.csv)
  ddc_compare_histories(plane_strain_consistency_${hex}_vs_${quad} plane_strain_arch_${hex} ${quad_run} 1e-10
    COLUMNS load_factor strain_energy external_work newton_iterations)
endforeach()

# Belos CG + MueLu on 3-D elasticity at 107k DOFs (block_3d, Refinement 5) on
# 2 ranks: with Ifpack2's default eigenvalue estimate for the Chebyshev
# smoother the V-cycle was indefinite here and CG broke down in its first
# solve ("non-positive p^H*A*p"); it converges in about 17 iterations per solve.
ddc_add_run_test(block_3d_belos_muelu_107k RANKS 2 FIXTURE
  ARGS ${PROJECT_SOURCE_DIR}/examples/block_3d.xml --set "Mesh/Bodies/Block/Box/Refinement=5"
    --set "Solver/Linear Solver/Type=Belos-MueLu" --set "Output/VTK=false"
    --output-dir ${DDC_RUNS}/block_3d_belos_muelu_107k
  REGEX "107163 DOFs.*step +1/1 +load 1 +Newton +2" LABELS example)
ddc_check_history(block_3d_belos_muelu_107k_iterations block_3d_belos_muelu_107k CHECKS "last:dual_iterations:<=:40")
