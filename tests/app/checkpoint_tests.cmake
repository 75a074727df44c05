# ---- Checkpoint and restart (docs/checkpoint.md; included by tests/app/CMakeLists.txt) ----------
# The file: every field type round-trips bit for bit; other format versions, non-checkpoints,
# other cases and missing fields are refused with the reason; the write is atomic.
find_package(GTest REQUIRED)
add_executable(test_checkpoint test_checkpoint.cc test_checkpoint_integrity.cc)
string(REPLACE "-std=c++17" "" DEAL_II_CXX_FLAGS "${DEAL_II_CXX_FLAGS}")
string(REGEX REPLACE "(^| )-g( |$)" " " DEAL_II_CXX_FLAGS "${DEAL_II_CXX_FLAGS}")
deal_ii_setup_target(test_checkpoint)
target_link_libraries(test_checkpoint dembridge_app GTest::gtest_main)
gtest_discover_tests(test_checkpoint DISCOVERY_TIMEOUT 60)
# Where a checkpoint's datasets lie in the file (checkpoint_corrupt.py).
add_executable(checkpoint_layout checkpoint_layout.cc)
deal_ii_setup_target(checkpoint_layout)
# Kill -9 and resume (checkpoint_resume.py): killed after a checkpoint, between checkpoints, in
# the middle of writing one, and by a real `kill -9` from outside; each resumed run ends with
# every output file identical byte for byte to the uninterrupted run's (summary.json without
# its timing and provenance keys). One thread. Also the refusals: another case, a fresh run into
# a folder holding a checkpoint, --resume without a checkpoint, the static solver.
# an explicit specimen: the cubic compression at r = 12.5 mm (160 spheres), constant rate
app_python_test(checkpoint_resume_specimen checkpoint_resume.py
  $<TARGET_FILE:dembridge> ${EX}/compression_cubic.prm ${OUT}/checkpoint_specimen
  --set "Simulation/solver=explicit" --set "Particles/radius=0.0125"
  --set "Group corner_y/box min=0, 0.08, 0" --set "Group corner_y/box max=0.02, 0.1, 0.02"
  --set "Load compression/type=velocity" --set "Load compression/value=-2.5e-4, 0, 0"
  --set "Load compression/ramp time=0.002" --set "Simulation/end time=0.006"
  --set "Output/snapshot interval=400" --set "Output/checkpoint interval=0.0015")
# broken bonds and contacts: compression_failure.prm with r = 12.5 mm (162 spheres, 412
# brittle bonds, about 325 of them broken), platens (walls) and the linear contact law, loaded
# 25 times faster to past the peak; bonds break with contacts from t = 0.4 ms, the first
# checkpoint is at 1 ms
app_python_test(checkpoint_resume_failure checkpoint_resume.py
  $<TARGET_FILE:dembridge> ${EX}/compression_failure.prm ${OUT}/checkpoint_failure
  --expect-cracks --set "Particles/radius=0.0125"
  --set "Wall upper/velocity=-0.5, 0, 0" --set "Wall upper/ramp time=0.0002"
  --set "Simulation/end time=0.005" --set "Output/snapshot interval=500"
  --set "Output/checkpoint interval=0.001")
# bond classes (the columnar example cut down as example_columnar_tension, with contacts):
# the classes come back from the checkpoint, so cracks.csv's class and grains columns and the
# bonds' class array match the uninterrupted run's byte for byte (without them in the
# checkpoint the first resumed bond file differs)
app_python_test(checkpoint_resume_columnar checkpoint_resume.py
  $<TARGET_FILE:dembridge> ${EX}/columnar_tension.prm ${OUT}/checkpoint_columnar
  --expect-cracks --set "Particles/box size=0.06, 0.04, 0.04"
  --set "Microstructure/column diameter=0.015" --set "Group corner_y/point=0, 0.04, 0"
  --set "Load pull/value=2.4e-5, 0, 0" --set "Output/checkpoint interval=0.0015"
  --set "Contacts/model=linear" --set "Contacts/normal stiffness=1.5e7"
  --set "Contacts/friction coefficient=0.5")
# a pressure that follows the axial stress (examples/columnar_biaxial.prm at R = 0.3 cut down
# to 0.04 x 0.04 x 0.03 m, 421 spheres, about 700 bonds broken): the last step's pressure
# comes back from the checkpoint (without it the resumed history.csv differs)
app_python_test(checkpoint_resume_pressure checkpoint_resume.py
  $<TARGET_FILE:dembridge> ${EX}/columnar_biaxial.prm ${OUT}/checkpoint_pressure
  --expect-cracks --set "Load confine/ratio=0.3"
  --set "Particles/box size=0.04, 0.04, 0.03" --set "Load drive/area=0.0012"
  --set "Load confine/area=0.0012" --set "Load drive/value=-8e-5, 0, 0"
  --set "Output/checkpoint interval=0.001")
set_tests_properties(checkpoint_resume_pressure PROPERTIES TIMEOUT 300)
set_tests_properties(checkpoint_resume_specimen checkpoint_resume_failure
                     checkpoint_resume_columnar PROPERTIES TIMEOUT 300)
# A damaged checkpoint (256 seeded random bytes at 10, 30, 50, 70 and 90 % of the file) is
# refused naming the file and the dataset the bytes lie in, leaving the folder as it was, or
# (bytes nothing reads) resumes to the uninterrupted run's files (checkpoint_corrupt.py); the
# DEM specimen above, and the coupled and FE cases below.
app_python_test(checkpoint_corrupt_dem checkpoint_corrupt.py
  $<TARGET_FILE:dembridge> $<TARGET_FILE:checkpoint_layout> ${EX}/compression_cubic.prm
  ${OUT}/checkpoint_corrupt_dem
  --set "Simulation/solver=explicit" --set "Particles/radius=0.0125"
  --set "Group corner_y/box min=0, 0.08, 0" --set "Group corner_y/box max=0.02, 0.1, 0.02"
  --set "Load compression/type=velocity" --set "Load compression/value=-2.5e-4, 0, 0"
  --set "Load compression/ramp time=0.002" --set "Simulation/end time=0.006"
  --set "Output/snapshot interval=400" --set "Output/checkpoint interval=0.0015")
set_tests_properties(checkpoint_corrupt_dem PROPERTIES TIMEOUT 300)
# Write errors name the file and the system's reason (write_errors.py): a full disk (/dev/full
# in place of summary.json.part, particle_stress.csv.part or checkpoint.h5.tmp of a resumed
# run: "No space left on device") and a 4 KiB file size limit (RLIMIT_FSIZE, SIGXFSZ ignored:
# "File too large" for the first snapshot, or history.csv.part without snapshots)
app_python_test(write_errors_name_the_reason write_errors.py
  $<TARGET_FILE:dembridge> ${EX}/compression_cubic.prm ${OUT}/write_errors 100
  --set "Simulation/solver=explicit" --set "Particles/radius=0.0125"
  --set "Group corner_y/box min=0, 0.08, 0" --set "Group corner_y/box max=0.02, 0.1, 0.02"
  --set "Load compression/type=velocity" --set "Load compression/value=-2.5e-4, 0, 0"
  --set "Load compression/ramp time=0.002" --set "Simulation/end time=0.001"
  --set "Output/checkpoint interval=0.0001")
set_tests_properties(write_errors_name_the_reason PROPERTIES TIMEOUT 120)
# a coupled run: tests/coupling/coupled_pull.prm with its notch in the particle
# region (850 spheres, 8,712 FE DoFs), 0.8 ms (311 steps): the ligament's 50 bonds break from
# t = 0.49 ms; checkpoints every 0.2 ms (78 steps). Killed after the first checkpoint, late
# (resumed from t = 0.6 ms, bonds broken) and in the second checkpoint's write; snapshots of
# both sides every 100 steps.
if(TARGET dembridge_coupling)
  app_python_test(checkpoint_resume_coupled checkpoint_resume.py
    $<TARGET_FILE:dembridge> ${PROJECT_SOURCE_DIR}/tests/coupling/coupled_pull.prm
    ${OUT}/checkpoint_coupled --coupled --expect-cracks
    --set "Particles/remove box min=0.12, -1, -1"
    --set "Particles/remove box max=0.13, 1, 0.05" --set "Simulation/end time=0.0008"
    --set "Output/write vtu=true" --set "Output/snapshot interval=100"
    --set "Output/checkpoint interval=0.0002")
  set_tests_properties(checkpoint_resume_coupled PROPERTIES TIMEOUT 300)
  app_python_test(checkpoint_corrupt_coupled checkpoint_corrupt.py
    $<TARGET_FILE:dembridge> $<TARGET_FILE:checkpoint_layout>
    ${PROJECT_SOURCE_DIR}/tests/coupling/coupled_pull.prm ${OUT}/checkpoint_corrupt_coupled
    --set "Particles/remove box min=0.12, -1, -1"
    --set "Particles/remove box max=0.13, 1, 0.05" --set "Simulation/end time=0.0008"
    --set "Output/checkpoint interval=0.0002")
  set_tests_properties(checkpoint_corrupt_coupled PROPERTIES TIMEOUT 300)
  # the same under `mpirun -np 2` (the continuum split over two ranks, the particles on rank
  # 0): killed after the first checkpoint, late, in the second checkpoint's write and by a
  # `kill -9` of the whole job; each resumed np 2 run ends with the np 2 reference's files.
  # A checkpoint is resumed on as many ranks as wrote it: np 2 on 1 and np 1 on 2 are refused
  # in one line naming both counts (checkpoint_ranks.py).
  if(MPIEXEC_EXECUTABLE)
    app_python_test(checkpoint_resume_coupled_np2 checkpoint_resume.py
      $<TARGET_FILE:dembridge> ${PROJECT_SOURCE_DIR}/tests/coupling/coupled_pull.prm
      ${OUT}/checkpoint_coupled_np2 --coupled --expect-cracks
      --np 2 --mpiexec ${MPIEXEC_EXECUTABLE}
      --set "Particles/remove box min=0.12, -1, -1"
      --set "Particles/remove box max=0.13, 1, 0.05" --set "Simulation/end time=0.0008"
      --set "Output/write vtu=true" --set "Output/snapshot interval=100"
      --set "Output/checkpoint interval=0.0002")
    app_python_test(checkpoint_coupled_other_rank_count_refused checkpoint_ranks.py
      $<TARGET_FILE:dembridge> ${MPIEXEC_EXECUTABLE}
      ${PROJECT_SOURCE_DIR}/tests/coupling/coupled_pull.prm
      ${OUT}/checkpoint_coupled_ranks --set "Simulation/end time=0.0008"
      --set "Output/checkpoint interval=0.0002")
    set_tests_properties(checkpoint_resume_coupled_np2 checkpoint_coupled_other_rank_count_refused
      PROPERTIES TIMEOUT 300 PROCESSORS 2 ENVIRONMENT "${APP_MPI_ENV}")
  else()
    skipped_test(checkpoint_resume_coupled_np2 "mpirun not found")
    skipped_test(checkpoint_coupled_other_rank_count_refused "mpirun not found")
  endif()
endif()
# an FE dynamics run (tests/app/fem_vibration.prm: a bar in free axial vibration, 567 DoFs,
# 600 steps, snapshots every 100): checkpoints every 1.5 ms (110 steps); killed after the
# first, late (step 438), in the second checkpoint's write and from outside, on one rank and
# under `mpirun -np 2`; a checkpoint resumed on another rank count is refused
if(TARGET dembridge_fem)
  app_python_test(checkpoint_resume_fem checkpoint_resume.py
    $<TARGET_FILE:dembridge> ${CMAKE_CURRENT_SOURCE_DIR}/fem_vibration.prm
    ${OUT}/checkpoint_fem --fem --set "Output/checkpoint interval=0.0015")
  set_tests_properties(checkpoint_resume_fem PROPERTIES TIMEOUT 300)
  app_python_test(checkpoint_corrupt_fem checkpoint_corrupt.py
    $<TARGET_FILE:dembridge> $<TARGET_FILE:checkpoint_layout>
    ${CMAKE_CURRENT_SOURCE_DIR}/fem_vibration.prm ${OUT}/checkpoint_corrupt_fem
    --set "Output/checkpoint interval=0.0015")
  set_tests_properties(checkpoint_corrupt_fem PROPERTIES TIMEOUT 300)
  if(MPIEXEC_EXECUTABLE)
    app_python_test(checkpoint_resume_fem_np2 checkpoint_resume.py
      $<TARGET_FILE:dembridge> ${CMAKE_CURRENT_SOURCE_DIR}/fem_vibration.prm
      ${OUT}/checkpoint_fem_np2 --fem --np 2 --mpiexec ${MPIEXEC_EXECUTABLE}
      --set "Output/checkpoint interval=0.0015")
    app_python_test(checkpoint_fem_other_rank_count_refused checkpoint_ranks.py
      $<TARGET_FILE:dembridge> ${MPIEXEC_EXECUTABLE}
      ${CMAKE_CURRENT_SOURCE_DIR}/fem_vibration.prm ${OUT}/checkpoint_fem_ranks
      --kill-after-step 113 --set "Output/checkpoint interval=0.0015")
    set_tests_properties(checkpoint_resume_fem_np2 checkpoint_fem_other_rank_count_refused
      PROPERTIES TIMEOUT 300 PROCESSORS 2 ENVIRONMENT "${APP_MPI_ENV}")
  else()
    skipped_test(checkpoint_resume_fem_np2 "mpirun not found")
    skipped_test(checkpoint_fem_other_rank_count_refused "mpirun not found")
  endif()
endif()
