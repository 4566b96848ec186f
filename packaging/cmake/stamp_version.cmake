# Run at build time: stamps the project version, and the git revision when the source is a git
# checkout, into a header for the programs and a text file for CPack. Files are rewritten only
# when the stamp changes, so an unchanged revision rebuilds nothing.
# In: SOURCE_DIR, PROJECT_VERSION, HEADER, TEXT.
set(version "${PROJECT_VERSION}")
find_program(GIT git)
if(GIT AND EXISTS "${SOURCE_DIR}/.git")
  execute_process(COMMAND "${GIT}" -C "${SOURCE_DIR}" rev-parse --short=10 HEAD
                  OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE failed ERROR_QUIET)
  if(NOT failed AND revision)
    set(version "${version}+git.${revision}")
  endif()
endif()
file(CONFIGURE OUTPUT "${HEADER}" CONTENT "#pragma once\n#define AIRR_VERSION \"${version}\"\n")
file(CONFIGURE OUTPUT "${TEXT}" CONTENT "${version}\n")
