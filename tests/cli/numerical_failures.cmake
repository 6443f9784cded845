# Numerical failure is detected, named and handled (issue 7 items 5, 6): non-finite
# values cut the step back and then stop saying "non-finite" (exit 3), never "invalid
# job"; an under-constrained body is reported as a singular macro matrix, not as an
# inverted element. Specs in tests/data/numerics/ (see their "title").
set(FE2_NUMERICS ${PROJECT_SOURCE_DIR}/tests/data/numerics)
fe2_cli_test(cli.numerics.newmark_overflowing_rates 3
             "failed after 2 cutbacks: non-finite macro displacement gradient"
             ARGS run ${FE2_NUMERICS}/newmark_tiny_step.json --out ${FE2_CLI_OUT}/numerics_newmark --overwrite)
fe2_cli_test(cli.numerics.under_constrained_is_singular 3
             "run stopped: step 0 [(]t = 0 → 1[)]: the macro matrix is singular: MUMPS found [1-9][0-9]* null pivot.*rigid-body.*cannot help"
             ARGS run ${FE2_NUMERICS}/under_constrained.json --out ${FE2_CLI_OUT}/numerics_singular --overwrite)
# A cut-back's retry starts from the committed units (issue 7 item 4): before, the
# retry reused the factor and modes of the failed, inverted iterate and failed too.
fe2_cli_test(cli.numerics.retry_after_cutback_converges 0
             "step +1/1 .*Newton +[0-9]+ .*cutbacks 1 "
             ARGS run ${FE2_NUMERICS}/beam_retry.json --out ${FE2_CLI_OUT}/numerics_retry --overwrite)
