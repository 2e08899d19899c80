# Writes OUTPUT, a C++ file defining wl::git_revision() (output/json_writer.h), from
# the git checkout at SOURCE_DIR: the short revision, "-dirty" when tracked files have
# changes, "unknown" outside git. Run at every build (CMakeLists.txt), so that a run
# records the revision it was built from; the file is rewritten only when it changes.
execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY "${SOURCE_DIR}"
                OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
execute_process(COMMAND git status --porcelain --untracked-files=no WORKING_DIRECTORY "${SOURCE_DIR}"
                OUTPUT_VARIABLE changes OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT revision)
  set(revision "unknown")
elseif(changes)
  string(APPEND revision "-dirty")
endif()
file(WRITE "${OUTPUT}.new" "#include \"output/json_writer.h\"\n\nnamespace wl {\nstd::string git_revision() { return \"${revision}\"; }\n}  // namespace wl\n")
configure_file("${OUTPUT}.new" "${OUTPUT}" COPYONLY)
file(REMOVE "${OUTPUT}.new")
