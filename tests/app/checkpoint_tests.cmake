# ---- Checkpoint and restart (docs/checkpoint.md; included by tests/app/CMakeLists.txt) ----------
# The file: every field type round-trips bit for bit; other format versions, non-checkpoints,
# other cases and missing fields are refused with the reason; the write is atomic.
find_package(GTest REQUIRED)
dembridge_dealii_program(test_checkpoint test_checkpoint.cc test_checkpoint_integrity.cc
                         LINK dembridge_app GTest::gtest_main)
gtest_discover_tests(test_checkpoint DISCOVERY_TIMEOUT 60)
# Where a checkpoint's datasets lie in the file (checkpoint_corrupt.py).
dembridge_dealii_program(checkpoint_layout checkpoint_layout.cc)
# Kill -9 and resume (checkpoint_resume.py): killed after a checkpoint, between checkpoints, in
# the middle of writing one, and by a real `kill -9` from outside; each resumed run ends with
# every output file identical byte for byte to the uninterrupted run's (summary.json without
# its timing and provenance keys). One thread. Also the refusals: another case, a fresh run into
# a folder holding a checkpoint, --resume without a checkpoint, the static solver.
# A damaged checkpoint (256 seeded random bytes at 10, 30, 50, 70 and 90 % of the file) is
# refused naming the file and the dataset the bytes lie in, leaving the folder as it was, or
# (bytes nothing reads) resumes to the uninterrupted run's files (checkpoint_corrupt.py).
# Under `mpirun -np 2`: each resumed np 2 run ends with the np 2 reference's files, and a
# checkpoint is resumed on as many ranks as wrote it: np 2 on 1 and np 1 on 2 are refused in one
# line naming both counts (checkpoint_ranks.py).
#
# checkpoint_case(NAME CASE [FLAGS flags...] SET overrides... [CORRUPT [CORRUPT_AS name]
#                 [CORRUPT_SET overrides...]] [RANKS checkpoint_ranks.py args...]):
# checkpoint_resume_NAME resumes CASE --set overrides (checkpoint_resume.py FLAGS) into
# OUT/checkpoint_NAME; with CORRUPT, checkpoint_corrupt_NAME (or _name) damages its checkpoint
# (CORRUPT_SET, the same overrides where not given); with RANKS, checkpoint_resume_NAME_np2 is
# the resume under `mpirun -np 2` and checkpoint_NAME_other_rank_count_refused the refusals.
# Five minutes each.
function(checkpoint_case name case)
  cmake_parse_arguments(T "CORRUPT" "CORRUPT_AS" "FLAGS;SET;CORRUPT_SET;RANKS" ${ARGN})
  dembridge_set_arguments(sets ${T_SET})
  set(run $<TARGET_FILE:dembridge> ${case})
  app_python_test(checkpoint_resume_${name} checkpoint_resume.py ${run} ${OUT}/checkpoint_${name}
                  ${T_FLAGS} ${sets} TIMEOUT 300)
  if(T_CORRUPT)
    if(NOT T_CORRUPT_AS)
      set(T_CORRUPT_AS ${name})
    endif()
    if(T_CORRUPT_SET)
      dembridge_set_arguments(sets ${T_CORRUPT_SET})
    endif()
    app_python_test(checkpoint_corrupt_${T_CORRUPT_AS} checkpoint_corrupt.py
      $<TARGET_FILE:dembridge> $<TARGET_FILE:checkpoint_layout> ${case}
      ${OUT}/checkpoint_corrupt_${T_CORRUPT_AS} ${sets} TIMEOUT 300)
  endif()
  if(NOT T_RANKS)
    return()
  endif()
  if(NOT MPIEXEC_EXECUTABLE)
    dembridge_skipped_test(checkpoint_resume_${name}_np2 "mpirun not found")
    dembridge_skipped_test(checkpoint_${name}_other_rank_count_refused "mpirun not found")
    return()
  endif()
  dembridge_set_arguments(sets ${T_SET})
  app_python_test(checkpoint_resume_${name}_np2 checkpoint_resume.py ${run}
    ${OUT}/checkpoint_${name}_np2 ${T_FLAGS} --np 2 --mpiexec ${MPIEXEC_EXECUTABLE} ${sets})
  app_python_test(checkpoint_${name}_other_rank_count_refused checkpoint_ranks.py
    $<TARGET_FILE:dembridge> ${MPIEXEC_EXECUTABLE} ${case} ${OUT}/checkpoint_${name}_ranks
    ${T_RANKS})
  set_tests_properties(checkpoint_resume_${name}_np2 checkpoint_${name}_other_rank_count_refused
    PROPERTIES TIMEOUT 300 PROCESSORS 2 ENVIRONMENT "${DEMBRIDGE_MPI_ENV}")
endfunction()

# An explicit specimen: the cubic compression at r = 12.5 mm (160 spheres), constant rate.
set(SPECIMEN "Simulation/solver=explicit" "Particles/radius=0.0125"
    "Group corner_y/box min=0, 0.08, 0" "Group corner_y/box max=0.02, 0.1, 0.02"
    "Load compression/type=velocity" "Load compression/value=-2.5e-4, 0, 0"
    "Load compression/ramp time=0.002")
checkpoint_case(specimen ${EX}/compression_cubic.prm CORRUPT CORRUPT_AS dem
  SET ${SPECIMEN} "Simulation/end time=0.006" "Output/snapshot interval=400"
      "Output/checkpoint interval=0.0015")
# Broken bonds and contacts: compression_failure.prm with r = 12.5 mm (162 spheres, 412
# brittle bonds, about 325 of them broken), platens (walls) and the linear contact law, loaded
# 25 times faster to past the peak; bonds break with contacts from t = 0.4 ms, the first
# checkpoint is at 1 ms.
checkpoint_case(failure ${EX}/compression_failure.prm FLAGS --expect-cracks
  SET "Particles/radius=0.0125" "Wall upper/velocity=-0.5, 0, 0" "Wall upper/ramp time=0.0002"
      "Simulation/end time=0.005" "Output/snapshot interval=500"
      "Output/checkpoint interval=0.001")
# Bond classes (the columnar example cut down as example_columnar_tension, with contacts):
# the classes come back from the checkpoint, so cracks.csv's class and grains columns and the
# bonds' class array match the uninterrupted run's byte for byte (without them in the
# checkpoint the first resumed bond file differs).
checkpoint_case(columnar ${EX}/columnar_tension.prm FLAGS --expect-cracks
  SET "Particles/box size=0.06, 0.04, 0.04" "Microstructure/column diameter=0.015"
      "Group corner_y/point=0, 0.04, 0" "Load pull/value=2.4e-5, 0, 0"
      "Output/checkpoint interval=0.0015" "Contacts/model=linear"
      "Contacts/normal stiffness=1.5e7" "Contacts/friction coefficient=0.5")
# Basal joints (examples/columnar_compression.prm cut down to 0.05 x 0.03 x 0.03 m, 1,147
# bonds of which 91 basal smooth joints, 14 of them broken by the end, and 337 grain-boundary
# bonds, all broken and sliding on their boundaries by the end): each basal bond's normal,
# its grain's c-axis, is the case's and comes back with the classes (without it the resumed
# basal bonds would follow the unified law and the files differ).
checkpoint_case(basal ${EX}/columnar_compression.prm FLAGS --expect-cracks
  SET "Particles/box size=0.05, 0.03, 0.03" "Group corner_y/point=0, 0.03, 0"
      "Load drive/value=-6e-5, 0, 0" "Microstructure/basal cone angle=30"
      "Bond class basal/smooth joint=true" "Bond class basal/shear strength=0.3e6"
      "Output/checkpoint interval=0.0015")
# A pressure that follows the axial stress (examples/columnar_biaxial.prm at R = 0.3 cut down
# to 0.04 x 0.04 x 0.03 m, 421 spheres, about 700 bonds broken): the last step's pressure
# comes back from the checkpoint (without it the resumed history.csv differs).
checkpoint_case(pressure ${EX}/columnar_biaxial.prm FLAGS --expect-cracks
  SET "Load confine/ratio=0.3" "Particles/box size=0.04, 0.04, 0.03"
      "Load drive/area=0.0012" "Load confine/area=0.0012" "Load drive/value=-8e-5, 0, 0"
      "Output/checkpoint interval=0.001")
# Write errors name the file and the system's reason (write_errors.py): a full disk (/dev/full
# in place of summary.json.part, particle_stress.csv.part or checkpoint.h5.tmp of a resumed
# run: "No space left on device") and a 4 KiB file size limit (RLIMIT_FSIZE, SIGXFSZ ignored:
# "File too large" for the first snapshot, or history.csv.part without snapshots).
dembridge_set_arguments(_write_errors ${SPECIMEN} "Simulation/end time=0.001"
                        "Output/checkpoint interval=0.0001")
app_python_test(write_errors_name_the_reason write_errors.py
  $<TARGET_FILE:dembridge> ${EX}/compression_cubic.prm ${OUT}/write_errors 100 ${_write_errors}
  TIMEOUT 120)
# A coupled run: tests/coupling/coupled_pull.prm with its notch in the particle region (850
# spheres, 8,712 FE DoFs), 0.8 ms (311 steps): the ligament's 50 bonds break from t = 0.49 ms;
# checkpoints every 0.2 ms (78 steps). Killed after the first checkpoint, late (resumed from
# t = 0.6 ms, bonds broken) and in the second checkpoint's write; snapshots of both sides every
# 100 steps. Under `mpirun -np 2` the continuum is split over two ranks, the particles on rank 0,
# and the whole job is killed by the outside `kill -9`.
if(TARGET dembridge_coupling)
  set(NOTCH_AND_CHECKPOINTS "Particles/remove box min=0.12, -1, -1"
      "Particles/remove box max=0.13, 1, 0.05" "Simulation/end time=0.0008")
  checkpoint_case(coupled ${PROJECT_SOURCE_DIR}/tests/coupling/coupled_pull.prm
    FLAGS --coupled --expect-cracks
    SET ${NOTCH_AND_CHECKPOINTS} "Output/write vtu=true" "Output/snapshot interval=100"
        "Output/checkpoint interval=0.0002"
    CORRUPT CORRUPT_SET ${NOTCH_AND_CHECKPOINTS} "Output/checkpoint interval=0.0002"
    RANKS --set "Simulation/end time=0.0008" --set "Output/checkpoint interval=0.0002")
endif()
# An FE dynamics run (tests/app/fem_vibration.prm: a bar in free axial vibration, 567 DoFs,
# 600 steps, snapshots every 100): checkpoints every 1.5 ms (110 steps); killed after the
# first, late (step 438), in the second checkpoint's write and from outside, on one rank and
# under `mpirun -np 2`; a checkpoint resumed on another rank count is refused.
if(TARGET dembridge_fem)
  checkpoint_case(fem ${CMAKE_CURRENT_SOURCE_DIR}/fem_vibration.prm FLAGS --fem
    SET "Output/checkpoint interval=0.0015" CORRUPT
    RANKS --kill-after-step 113 --set "Output/checkpoint interval=0.0015")
endif()
