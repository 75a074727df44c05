# Case files and the messages of bad input (included by tests/app/CMakeLists.txt; uses its
# run_and_check, error_test, app_python_test, OUT, EX and BAD).

# ---- JSON case files ----------------------------------------------------------------------------
# The cantilever of paper case 1 as a .json case (groups, a load named tip_load, numbers, a
# boolean, deal.II's long form of an entry, a load's own key named "value"), static solver:
# eq. 29's 8.534242 mm to 1e-6, as cantilever_static.
run_and_check(json_case_cantilever ${CMAKE_CURRENT_SOURCE_DIR}/data/cantilever.json
  json_case_cantilever CHECK tip_deflection near 8.534242e-3 1e-6 n_particles near 11 0
  n_bonds near 10 0)

# Round trip: an example's complete parameter set written as .json (deal.II's print of the
# ParameterHandler, summary.json's "parameters") runs to the .prm run's summary, every figure
# equal (tests/app/json_round_trip.py). The examples that run in a few seconds: those an example
# test above already runs as they are reuse its run; the others, 10 s to 50 s a run
# (bending_notched_failure, compression_failure, tension_failure, coupled_ball_region,
# coupled_bending, coupled_compression, coupled_compression_failure, coupled_notched_bending,
# fem_bending, fem_cantilever), are not run twice here: they use the same reader.
set(_json_round_trip_reused cantilever:cantilever_timoshenko compression_cubic:compression_cubic_static
    bending_cubic:bending_cubic_static fem_compression:fem_compression_app
    beam_simply_supported:beam_simply_supported beam_free_vibration:beam_free_vibration
    contact_two_spheres:contact_two_spheres)
set(_json_round_trip_run bending_random compression_hcp compression_random tension_random)
if(TARGET dembridge_coupling)
  list(APPEND _json_round_trip_run coupled_wave)
endif()
foreach(_pair IN LISTS _json_round_trip_reused)
  string(REPLACE ":" ";" _pair ${_pair})
  list(GET _pair 0 _example)
  list(GET _pair 1 _run)
  app_python_test(json_round_trip_${_example} json_round_trip.py $<TARGET_FILE:dembridge>
    ${EX}/${_example}.prm ${OUT}/json_round_trip_${_example} ${OUT}/${_run} AFTER ${_run})
endforeach()
foreach(_example IN LISTS _json_round_trip_run)
  app_python_test(json_round_trip_${_example} json_round_trip.py $<TARGET_FILE:dembridge>
    ${EX}/${_example}.prm ${OUT}/json_round_trip_${_example})
endforeach()

# JSON input deal.II's reader took silently or reported unclearly: a key or subsection given
# twice, a comment, a list; and the messages name the whole key (a name with '_' was cut).
set(JSON_CASE ${CMAKE_CURRENT_SOURCE_DIR}/data/cantilever.json)
error_test(json_duplicate_key ${BAD}/duplicate_key.json "duplicate_key.json: Particles/radius is set twice")
error_test(json_duplicate_subsection ${BAD}/duplicate_subsection.json "duplicate_subsection.json: subsection 'Particles' is given twice")
error_test(json_comment ${BAD}/comment.json "comment.json:3: JSON has no comments")
error_test(json_syntax ${BAD}/trailing_comma.json "trailing_comma.json:3: syntax error while parsing object key")
error_test(json_list_value ${BAD}/list_value.json "list_value.json: Particles/origin: a JSON list is no value; write the list as one string")
error_test(json_unknown_key ${BAD}/unknown_key.json "unknown_key.json: Bonds/stiffnes ratio: no such parameter in 'Bonds'")
error_test(json_value_pattern ${BAD}/negative_end_time.json "negative_end_time.json: Simulation/end time: the value '-5e-3' does not match \\[Double 0")
error_test(json_unknown_group_in_load ${JSON_CASE} "cantilever.json: Load tip_load/group: no group named 'tipp'" --set "Load tip_load/group=tipp")
error_test(json_load_not_listed ${JSON_CASE} "cantilever.json: subsection 'Load tip_load' is not named in Loads/names \\(it is empty\\)" --set "Loads/names=")
error_test(json_group_without_subsection ${JSON_CASE} "cantilever.json: Groups/names: 'free' is listed but the file has no 'subsection Group free'" --set "Groups/names=clamp, tip, free")

# ---- Messages that named the wrong thing, or nothing ----------------------------------------------
# A UTF-8 byte-order mark before the first line is read as absent: the static cantilever.
run_and_check(case_file_byte_order_mark ${CMAKE_CURRENT_SOURCE_DIR}/data/byte_order_mark.prm
  byte_order_mark CHECK tip_deflection near 8.534242e-3 1e-6)
error_test(case_file_is_directory ${BAD} "bad: is a directory, not a case file")
error_test(walls_named_twice ${EX}/compression_failure.prm "compression_failure.prm: Walls/names: 'lower' is listed twice" --set "Walls/names=lower, lower")
error_test(wall_not_listed ${EX}/compression_failure.prm "compression_failure.prm: subsection 'Wall upper' is not named in Walls/names \\(lower\\)" --set "Walls/names=lower")
error_test(group_not_listed ${EX}/cantilever.prm "cantilever.prm: subsection 'Group tip' is not named in Groups/names \\(clamp\\)" --set "Groups/names=clamp")
error_test(platen_not_a_wall ${EX}/compression_failure.prm "compression_failure.prm: Contacts/platens: 'nowhere' is not a wall \\(Walls/names = lower, upper\\)" --set "Contacts/platens=lower, nowhere")
error_test(set_names_a_section ${EX}/cantilever.prm "--set 'Bonds=1': 'Bonds' is a section, not a key \\(expected Section/Key=value" --set "Bonds=1")
error_test(set_without_value ${EX}/cantilever.prm "--set 'Bonds/youngs modulus': no '=value'" --set "Bonds/youngs modulus")
error_test(one_particle ${EX}/cantilever.prm "cantilever.prm: Particles: the case has one particle, and a bonded model needs at least two" --set "Particles/count=1")
# a relative Particles/file is resolved beside the case file, and the message shows where
error_test(particle_file_resolved ${BAD}/particle_file.prm "particle_file.prm: Particles/file: 'data/nope.csv' does not exist \\(looked for /.*/tests/app/bad/data/nope.csv\\)" --set "Particles/file=data/nope.csv")
if(TARGET dembridge_fem)
  # gmsh files deal.II would report as "The string <//> is not recognized", or echo the bytes of
  error_test(fem_mesh_geometry_script ${EX}/fem_bending.prm
    "fem_bending.prm: FEM/Mesh/file: .*specimen.geo: a gmsh geometry script, not a mesh; mesh it first \\(gmsh -3 .*specimen.geo writes .*specimen.msh\\)"
    --set "FEM/Mesh/file=${PROJECT_SOURCE_DIR}/meshes/specimen.geo")
  error_test(fem_mesh_not_msh ${EX}/fem_bending.prm
    "fem_bending.prm: FEM/Mesh/file: .*geometry_script.msh: line 1: not a gmsh .msh file: it begins with '// A gmsh geometry script saved as.*', not \\$MeshFormat"
    --set "FEM/Mesh/file=${BAD}/geometry_script.msh")
  error_test(fem_mesh_empty ${EX}/fem_bending.prm
    "fem_bending.prm: FEM/Mesh/file: .*empty.msh: the file is empty"
    --set "FEM/Mesh/file=${BAD}/empty.msh")
  error_test(fem_mesh_binary ${EX}/fem_bending.prm
    "fem_bending.prm: FEM/Mesh/file: .*binary.msh: line 2: a binary .msh file; only ASCII ones are read \\(convert it: gmsh .*binary.msh -save -format msh41 -o ASCII.msh\\)"
    --set "FEM/Mesh/file=${BAD}/binary.msh")
  error_test(fem_mesh_binary_body ${EX}/fem_bending.prm
    "fem_bending.prm: FEM/Mesh/file: .*binary_body.msh: line 3: binary data in a .msh file read as ASCII"
    --set "FEM/Mesh/file=${BAD}/binary_body.msh")
  error_test(fem_mesh_is_directory ${EX}/fem_bending.prm
    "fem_bending.prm: FEM/Mesh/file: '.*bad' is a directory, not a mesh file"
    --set "FEM/Mesh/file=${BAD}")
endif()
if(TARGET dembridge_coupling)
  error_test(region_geometry_script ${EX}/coupled_ball_region.prm
    "coupled_ball_region.prm: Coupling/particle region file: .*region_sphere.geo: a gmsh geometry script, not a mesh; mesh it first \\(gmsh -3 "
    --set "Coupling/particle region file=${PROJECT_SOURCE_DIR}/meshes/region_sphere.geo")
  error_test(region_empty ${EX}/coupled_ball_region.prm
    "coupled_ball_region.prm: Coupling/particle region file: .*empty.msh: the file is empty"
    --set "Coupling/particle region file=${BAD}/empty.msh")
  error_test(region_binary ${EX}/coupled_ball_region.prm
    "coupled_ball_region.prm: Coupling/particle region file: .*binary.msh: line 2: a binary .msh file"
    --set "Coupling/particle region file=${BAD}/binary.msh")
endif()
