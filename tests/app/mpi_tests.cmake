# Every command under `mpirun -np N` (included by tests/app/CMakeLists.txt): it works, or it
# refuses within 60 s with one line on rank 0's stderr, nothing on the others', exit code 1 and
# no folder (tests/app/expect_error_mpi.sh). Explicit particle runs work, with contacts, walls
# and checkpoints, and so does the static DEM solver (tests/distributed); the contact monitor, a
# static run's checkpoints and a pressure load's checkpoints refuse on more than one rank; FE and
# coupled runs work (coupled_compression_np2 and the coupled beams in tests/coupling,
# checkpoint_resume_fem_np2 and checkpoint_resume_coupled_np2 in checkpoint_tests.cmake).
if(MPIEXEC_EXECUTABLE)
  # mpi_error_test(name np regex subcommand args...): mpi_npNP_name, a minute at most
  function(mpi_error_test name np regex)
    dembridge_expect_error_mpi(mpi_np${np}_${name} ${np} ${OUT}/mpi_np${np}_${name} "${regex}" ${ARGN})
    set_tests_properties(mpi_np${np}_${name} PROPERTIES TIMEOUT 60)
  endfunction()
  # explicit DEM runs split their particles over the ranks, the static solver solves on them
  # together (tests/distributed: the cantilever, compression_hcp and the notched beam on 2 and 3
  # ranks against one); what does not run there is refused on every rank alike, printed once:
  # a static run whose supports leave a rigid-body mode free (the ranks' CG stops on it together)
  # and a static run with checkpoints
  if(TARGET dembridge_fem) # the static solver on several ranks is PETSc's
    mpi_error_test(run_dem_static_singular 2 "^dembridge: error: cantilever.prm: static solver: the supports leave rigid-body motion free .*\\(PETSc CG\\+GAMG on 2 ranks .* did not converge in [0-9]+ iterations\\)$"
                   run ${EX}/cantilever.prm --set "Simulation/solver=static" --set "Group clamp/fixed=ux")
  endif()
  mpi_error_test(run_dem_static_checkpoint 3 "^dembridge: error: cantilever.prm: Output/checkpoint interval: the static solver has no time steps to checkpoint"
                 run ${EX}/cantilever.prm --set "Simulation/solver=static" --set "Output/checkpoint interval=0.01")
  # contacts and walls run on several ranks (distributed_compression_failure_np{2,3} in
  # tests/distributed); the record of the first contact does not
  mpi_error_test(run_dem_contact_monitor 2 "contact_two_spheres.prm: Contacts/monitor: the first contact's record does not run on several MPI ranks"
                 run ${EX}/contact_two_spheres.prm)
  # DEM checkpoints resume on any number of ranks, written on one or several (tests/distributed:
  # distributed_compression_failure_resume, _resume_from_one)
  mpi_error_test(verify 2 "^dembridge: error: verify runs on one MPI rank \\(the FE model is small\\), this job has 2"
                 verify ${EX}/compression_cubic.prm --youngs-modulus 3e9 --poisson-ratio 0.2)
  mpi_error_test(elasticity 2 "^dembridge: error: elasticity runs on one MPI rank"
                 elasticity ${EX}/compression_cubic.prm)
  mpi_error_test(calibrate 2 "^dembridge: error: calibrate runs on one MPI rank \\(its static solves are not shared over ranks\\), this job has 2"
                 calibrate ${EX}/calibrate_hcp.prm)
  if(TARGET dembridge_coupling)
    mpi_error_test(compare 2 "^dembridge: error: compare runs on one MPI rank"
                   compare ${EX}/coupled_compression.prm)
    # bad input of a coupled run, found on every rank: printed once
    mpi_error_test(coupled_bad_input 2 "coupled_compression.prm: Particles/origin: the particle region .* lies outside the FE domain"
                   run ${EX}/coupled_compression.prm --set "Particles/origin=0.2, 0, 0")
  endif()
  if(TARGET dembridge_fem)
    # bad input of an FE run, found by every rank inside the run (after the folder was made)
    mpi_error_test(fem_bad_input 2 "fem_bending.prm: FEM/Boundary conditions: the supports leave rigid-body modes free"
                   run ${EX}/fem_bending.prm --set "FEM/Boundary conditions/boundaries=" --set "FEM/Mesh/refinements=0")
  endif()
  mpi_error_test(usage_error 2 "^dembridge: error: unknown subcommand 'frobnicate'" frobnicate)
  mpi_error_test(missing_case_file 2 "^dembridge: error: nope.prm: no such case file" run nope.prm)
  # print-parameters and --version print once, as on one rank
  dembridge_check_output(mpi_np2_print_parameters --mpi ${MPIEXEC_EXECUTABLE} 2
    --same-on-one-rank --stdout ${OUT}/mpi_np2_print_parameters.txt
    -- $<TARGET_FILE:dembridge> print-parameters TIMEOUT 60 PROCESSORS 2 MPI_ENV)
  dembridge_check_output(mpi_np2_version --mpi ${MPIEXEC_EXECUTABLE} 2 --same-on-one-rank
    -- $<TARGET_FILE:dembridge> --version TIMEOUT 60 PROCESSORS 2 MPI_ENV)
  # an error one rank meets alone ends the job within seconds (tests/app/mpi_lone_failure.sh)
  if(TARGET dembridge_fem)
    dembridge_test(mpi_np2_lone_failure TIMEOUT 180 PROCESSORS 2 MPI_ENV
      COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/mpi_lone_failure.sh ${MPIEXEC_EXECUTABLE}
              $<TARGET_FILE:dembridge> ${EX}/fem_compression.prm ${OUT}/mpi_np2_lone_failure)
  endif()
else()
  foreach(_t mpi_np2_run_dem_static_singular mpi_np2_print_parameters mpi_np2_lone_failure)
    dembridge_skipped_test(${_t} "mpirun not found")
  endforeach()
endif()
