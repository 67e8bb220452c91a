# Tests and scripts carry their own data: no file under tests/ or scripts/ may refer to the
# project's shared folder beside the repository (a clone alone in its folder has none).
# Included by tests/CMakeLists.txt at configure time, and run as the test "self_contained":
#   cmake -DQF_SOURCE_DIR=<repository root> -P tests/check_self_contained.cmake
if(NOT QF_SOURCE_DIR)
  message(FATAL_ERROR "check_self_contained.cmake: set QF_SOURCE_DIR to the repository root")
endif()
# The patterns are written so that this file does not match them itself.
set(_qf_outside_refs "[.][.]/shared|QF_SHARED_[D]IR")
file(GLOB_RECURSE _qf_files LIST_DIRECTORIES false "${QF_SOURCE_DIR}/tests/*" "${QF_SOURCE_DIR}/scripts/*")
set(_qf_offenders "")
foreach(_qf_file IN LISTS _qf_files)
  if(_qf_file MATCHES "/node_modules/")
    continue()
  endif()
  file(STRINGS "${_qf_file}" _qf_hits REGEX "${_qf_outside_refs}")
  if(_qf_hits)
    file(RELATIVE_PATH _qf_rel "${QF_SOURCE_DIR}" "${_qf_file}")
    list(GET _qf_hits 0 _qf_first)
    string(STRIP "${_qf_first}" _qf_first)
    string(APPEND _qf_offenders "\n  ${_qf_rel}: ${_qf_first}")
  endif()
endforeach()
if(_qf_offenders)
  message(FATAL_ERROR "Tests and scripts must not read the shared folder beside the repository "
                      "(a fresh clone has none); "
                      "put the data under tests/data/ instead:${_qf_offenders}")
endif()
