# Writes the build facts header. CMake runs this at every build (target latfrac_version),
# so a binary built after a commit or an edit names the commit it was built from; run at
# configure time only, the stamp went stale. configure_file rewrites the header only when
# it changes, so an unchanged commit recompiles nothing.
# Inputs: SOURCE_DIR, OUTPUT, PROJECT_VERSION.
execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE LATFRAC_GIT_COMMIT OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET)
execute_process(COMMAND git status --porcelain --untracked-files=no WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE LATFRAC_GIT_DIRTY OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT LATFRAC_GIT_COMMIT)
  set(LATFRAC_GIT_COMMIT "unknown")
elseif(LATFRAC_GIT_DIRTY)
  set(LATFRAC_GIT_COMMIT "${LATFRAC_GIT_COMMIT}-dirty")
endif()
configure_file(${SOURCE_DIR}/cmake/version.h.in ${OUTPUT} @ONLY)
