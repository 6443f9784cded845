# Bad input that used to get through (issue 7, items 11-14): each case checks the exit
# code 2 and the message that names the file or key, the value and what was expected.
# Included from tests/cli/CMakeLists.txt (uses fe2_cli_test, FE2_CLI_BAD, FE2_CLI_OUT).

# --- Memory (item 11): a 100³ unit is refused from its estimate, in seconds, naming the
# key, the estimate and the limit; validate builds nothing, run writes nothing.
set(huge "/models/myocardium/unit/resolution: got [[]100, 100, 100[]]. .*need.* ≈ [0-9.]+ [GT]B .*2999997 DOF.*above the memory limit of [0-9.]+ [kMGT]?B")
fe2_cli_test(cli.bad_input.huge_unit.validate 2 "${huge}"
             ARGS validate ${FE2_CLI_BAD}/huge_unit.json)
fe2_cli_test(cli.bad_input.huge_unit.run 2 "${huge}"
             ABSENT ${FE2_CLI_OUT}/huge_unit
             ARGS run ${FE2_CLI_BAD}/huge_unit.json --out ${FE2_CLI_OUT}/huge_unit)
set_tests_properties(cli.bad_input.huge_unit.validate cli.bad_input.huge_unit.run
                     PROPERTIES TIMEOUT 15)
# The shipped scene passes the default limit (see cli.validate.fe2_beam) but not 1M.
set(tiny "/models/myocardium/unit/resolution: got [[]8, 4, 4[]]. .*381 DOF.*above the memory limit of 1[.]0 MB [(]--memory-limit 1M[)]")
fe2_cli_test(cli.bad_input.memory_limit_1M.validate 2 "${tiny}"
             ARGS validate --memory-limit 1M ${PROJECT_SOURCE_DIR}/configs/fe2_beam.json)
fe2_cli_test(cli.bad_input.memory_limit_1M.run 2 "${tiny}"
             ABSENT ${FE2_CLI_OUT}/memory_limit_1M
             ARGS run ${PROJECT_SOURCE_DIR}/configs/fe2_beam.json --memory-limit 1M
                  --out ${FE2_CLI_OUT}/memory_limit_1M)
fe2_cli_test(cli.validate.memory_limit_1G 0 "fe2_beam[.]json: OK: .*unit memory ≈ [0-9.]+ MB on one rank [(]limit 1[.]1 GB[)]"
             ARGS validate --memory-limit 1G ${PROJECT_SOURCE_DIR}/configs/fe2_beam.json)
fe2_cli_test(cli.bad_input.memory_limit_syntax 2
             "--memory-limit: got '12Q', expected a positive size in bytes, optionally with a suffix k, M, G or T"
             ARGS validate --memory-limit 12Q ${FE2_CLI_BAD}/small_valid.json)
# Found by fuzz_spec (tests/fuzz): a size whose scaled value overflows was +inf bytes.
fe2_cli_test(cli.bad_input.memory_limit_overflow 2
             "--memory-limit: got '1e308T', expected a positive size in bytes"
             ARGS validate --memory-limit 1e308T ${FE2_CLI_BAD}/small_valid.json)
# farm.factor_memory_budget (issue #11): a budget below one unit's factor (by the memory
# estimate) is refused naming the key, the value and the smallest useful budget, before
# anything runs; a text that is no size names the key and the text.
set(budget "/farm/factor_memory_budget: got \"100k\" [(]102[.]4 kB[)], expected at least 185280 bytes [(]≈ 185[.]3 kB, one factor of model 'muscle' by the memory estimate: 189 DOF")
fe2_cli_test(cli.bad_input.factor_budget_too_small.validate 2 "${budget}"
             ARGS validate ${FE2_CLI_BAD}/factor_budget_too_small.json)
fe2_cli_test(cli.bad_input.factor_budget_too_small.run 2 "${budget}"
             ABSENT ${FE2_CLI_OUT}/factor_budget_too_small
             ARGS run ${FE2_CLI_BAD}/factor_budget_too_small.json --out ${FE2_CLI_OUT}/factor_budget_too_small)
fe2_cli_test(cli.bad_input.factor_budget_malformed 2
             "/farm/factor_memory_budget: got '2 GB', expected a positive size in bytes, optionally with a suffix k, M, G or T"
             ARGS validate ${FE2_CLI_BAD}/factor_budget_malformed.json)
fe2_cli_test(cli.validate.factor_budget_valid 0 "factor_budget_valid[.]json: OK: .*6 FE² units"
             ARGS validate ${FE2_CLI_BAD}/factor_budget_valid.json)
# The memory limit counts a rank's factors up to the budget: six units (≈ 4.9 MB by the
# estimate) are refused under --memory-limit 4.5M with a budget above their factors, and
# run with a 400k budget (≈ 4.3 MB), dropping and rebuilding factors as they go.
fe2_cli_test(cli.bad_input.factor_budget_above_factors_memory_limit 2
             "/models/muscle/unit/resolution: got [[]4, 4, 4[]].* needing ≈ 4[.]9 MB .*above the memory limit of 4[.]7 MB .*or a smaller farm[.]factor_memory_budget"
             ABSENT ${FE2_CLI_OUT}/factor_budget_above_factors
             ARGS run ${FE2_CLI_BAD}/factor_budget_valid.json --memory-limit 4.5M --out ${FE2_CLI_OUT}/factor_budget_above_factors)
fe2_cli_test(cli.run.factor_budget_fits_memory_limit 0 "done in .*1 steps"
             ARGS run ${FE2_CLI_BAD}/factor_budget_fits_limit.json --memory-limit 4.5M
                  --out ${FE2_CLI_OUT}/factor_budget_fits_limit --overwrite)

# --- Nesting (item 12): 70,000 nested arrays crashed the reader (SIGSEGV).
set(deep_json ${CMAKE_CURRENT_BINARY_DIR}/deep.json)
string(REPEAT "[" 70000 open)
string(REPEAT "]" 70000 close)
file(WRITE ${deep_json} "${open}${close}\n")
fe2_cli_test(cli.bad_input.deep_json.validate 2
             "spec file '[^']*deep[.]json': nesting depth 65 at /0/0/.* exceeds the limit of 64"
             ARGS validate ${deep_json})

# --- Files and keys named (item 13).
fe2_cli_test(cli.bad_input.directory_as_spec.validate 2
             "spec file '[^']*/tests/data/bad' is a directory, expected a JSON file"
             ARGS validate ${FE2_CLI_BAD})
fe2_cli_test(cli.bad_input.number_overflow.validate 2
             "spec file '[^']*overflow[.]json' at /time/t_end: .*number overflow parsing '1e999'"
             ARGS validate ${FE2_CLI_BAD}/overflow.json)
fe2_cli_test(cli.bad_input.duplicate_key.validate 2
             "spec file '[^']*duplicate_key[.]json': duplicate key 'E' at /models/muscle/material/E"
             ARGS validate ${FE2_CLI_BAD}/duplicate_key.json)
fe2_cli_test(cli.bad_input.missing_region.validate 2
             "/assign/regions/3: got region \"3\", which is not in the mesh box generator; expected one of its regions [(]1, 2[)]$"
             ARGS validate ${FE2_CLI_BAD}/missing_region.json)
fe2_cli_test(cli.validate.two_regions 0 "two_regions[.]json: OK: 12 nodes, 12 tetrahedra"
             ARGS validate ${FE2_CLI_BAD}/two_regions.json)
# Command-line usage errors are bad input: exit 2 (CLI11's own codes are 105, 106, ...).
fe2_cli_test(cli.usage.missing_argument 2 "spec is required" ARGS validate)
fe2_cli_test(cli.usage.missing_out 2 "--out is required"
             ARGS run ${FE2_CLI_BAD}/small_valid.json)
fe2_cli_test(cli.usage.bad_choice 2 "--policy: fastest not in [{]"
             ARGS run ${FE2_CLI_BAD}/small_valid.json --out ${FE2_CLI_OUT}/x --policy fastest)
# A malformed test hook must not silently test nothing.
foreach(fault "unit=x" "unit=1,kind=stall_forever" "unit=1,steps=2")
  string(MAKE_C_IDENTIFIER "${fault}" id)
  if(fault STREQUAL "unit=x")
    set(why "unit=x is not a non-negative integer")
  elseif(fault MATCHES "kind")
    set(why "unknown kind 'stall_forever'; expected a kind [(]numerical, fatal, stall, hang, kill[)]")
  else()
    set(why "unknown field 'steps'; expected a field [(]unit, step, kind[)]; did you mean \"step\"[?]")
  endif()
  add_test(NAME cli.bad_input.fault_env.${id}
           COMMAND ${FE2_CLI_EXPECT} --absent ${FE2_CLI_OUT}/fault_${id} 2
                   "FE2HEART_FAULT='${fault}': ${why}. expected unit=K"
                   -- env FE2HEART_FAULT=${fault} $<TARGET_FILE:fe2heart>
                   run ${FE2_CLI_BAD}/small_valid.json --out ${FE2_CLI_OUT}/fault_${id})
  set_tests_properties(cli.bad_input.fault_env.${id} PROPERTIES LABELS unit
                       ENVIRONMENT "${FE2_TEST_ENV}" TIMEOUT 90)
endforeach()

# --- Gmsh micro cells (item 14): a hex volume in no physical group has no material.
fe2_cli_test(cli.bad_input.untagged_cell.validate 2
             "mesh file '[^']*untagged_cell[.]msh' line 77: hexahedra of volume entity 1 [(]elements 1..8[)] belong to no physical group"
             ARGS validate ${FE2_CLI_BAD}/untagged_unit.json)

# --- Blood (issue 30): a fluid region that is also wall, a boundary on a set the mesh
# lacks, an element of the other order: each names the key, the value and what fits.
fe2_cli_test(cli.bad_input.fluid_region_is_wall 2
             "/fluid/regions: got [[]\"blood\"[]], expected regions that are not wall [(]region 1 is; set /mesh/wall_regions"
             ARGS validate ${FE2_CLI_BAD}/fluid_region_is_wall.json)
fe2_cli_test(cli.bad_input.fluid_unknown_set 2
             "/fluid/boundaries/4/set: got \"outlett\", expected a named boundary face set of the mesh [(].*outlet.*[)]; did you mean \"outlet\"[?]"
             ABSENT ${FE2_CLI_OUT}/fluid_unknown_set
             ARGS run ${FE2_CLI_BAD}/fluid_unknown_set.json --out ${FE2_CLI_OUT}/fluid_unknown_set)
fe2_cli_test(cli.bad_input.fluid_element_of_other_order 2
             "/fluid/element: got \"p1p1\", expected the element of the mesh's order [(]quadratic[)]: \"taylor_hood\", \"taylor_hood_supg\" or \"auto\""
             ARGS validate ${FE2_CLI_BAD}/fluid_element_of_other_order.json)
# A valve ring needs a circulation, and a cavity of it.
fe2_cli_test(cli.bad_input.fluid_valve_without_circulation 2
             "/fluid/boundaries/4/kind: got \"valve\", expected flux or pressure [(]a valve ring needs /circulation: its flow[)]"
             ARGS validate ${FE2_CLI_BAD}/fluid_valve_without_circulation.json)
# Two-way blood fills every cavity of the circulation: it needs their valve rings.
fe2_cli_test(cli.bad_input.fluid_two_way_without_rings 2
             "/fluid/coupling: got \"two_way\", expected \"one_way\", or valve rings for the circulation's cavity 'lv'"
             ARGS validate ${FE2_CLI_BAD}/fluid_two_way_without_rings.json)
# The LV generator's own checks of its cavity's rings name the spec path.
fe2_cli_test(cli.bad_input.lv_cavity_rings_overlap 2
             "/mesh: make_lv_mesh: ring 'mitral' and ring 'aortic': gap = -1.5: expected discs that do not overlap"
             ARGS validate ${FE2_CLI_BAD}/lv_cavity_rings_overlap.json)
# A flux face or valve ring that another condition holds at every node passes nothing;
# two rings for one valve would split its flow.
fe2_cli_test(cli.bad_input.fluid_flux_face_held 2
             "/fluid/boundaries/3/set: 'mitral' [(]a valve ring[)]: every node of its faces is held by a velocity, no_slip or moving_wall set"
             ARGS validate ${FE2_CLI_BAD}/fluid_flux_face_held.json)
fe2_cli_test(cli.bad_input.fluid_two_rings_one_valve 2
             "/fluid/boundaries/3/side: got \"inflow\", expected the inflow valve of cavity 'lv' once [(]ring 'mitral' is already its ring[)]"
             ARGS validate ${FE2_CLI_BAD}/fluid_two_rings_one_valve.json)
fe2_cli_test(cli.bad_input.fluid_valve_unknown_cavity 2
             "/fluid/boundaries/3/cavity: got \"lvv\", expected a cavity of the circulation [(]lv[)]; did you mean \"lv\"[?]"
             ARGS validate ${FE2_CLI_BAD}/fluid_valve_unknown_cavity.json)

# farm.threads_per_rank (issue #32 §3): units that may factor with MUMPS (it calls MPI,
# which helper threads may not) are refused naming the model, the keys and what runs.
fe2_cli_test(cli.bad_input.threads_with_mumps.run 2
             "farm.threads_per_rank = 2: model 'muscle' factors in single precision with MUMPS [(]/models/muscle/unit/solver: single_factor 'supernodal', factorization 'auto'[)].*expected farm.threads_per_rank 1, or solver.factorization \"cholesky\""
             ABSENT ${FE2_CLI_OUT}/threads_with_mumps
             ARGS run ${FE2_CLI_BAD}/threads_with_mumps.json --out ${FE2_CLI_OUT}/threads_with_mumps)
