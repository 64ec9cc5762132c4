# Writes OUTPUT: one ctest test per GoogleTest suite of TEST_EXECUTABLE,
# unit.<suite>, which runs that suite's cases in one process, and the list
# of their names in ashlar_unit_suites. Run after every link of the test
# binary (tests/CMakeLists.txt).
#   cmake -D TEST_EXECUTABLE=<binary> -D OUTPUT=<file> -P unit_suites.cmake
foreach(variable TEST_EXECUTABLE OUTPUT)
  if(NOT ${variable})
    message(FATAL_ERROR "unit_suites.cmake: ${variable} is not set")
  endif()
endforeach()

execute_process(COMMAND ${TEST_EXECUTABLE} --gtest_list_tests
  OUTPUT_VARIABLE listing ERROR_VARIABLE errors RESULT_VARIABLE result TIMEOUT 60)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${TEST_EXECUTABLE} --gtest_list_tests failed (${result}):\n${errors}")
endif()

# A suite's line starts in the first column and ends with its name and a
# dot, before any "# TypeParam = ..." comment; its cases follow indented.
string(REPLACE ";" "\\;" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")
set(content "")
set(suites "")
foreach(line IN LISTS lines)
  if(line MATCHES "^([^ #][^ ]*)\\.( |$)")
    set(suite ${CMAKE_MATCH_1})
    string(APPEND content
      "add_test([==[unit.${suite}]==] [==[${TEST_EXECUTABLE}]==] [==[--gtest_filter=${suite}.*]==])\n")
    list(APPEND suites "unit.${suite}")
  endif()
endforeach()
if(NOT suites)
  message(FATAL_ERROR "${TEST_EXECUTABLE} --gtest_list_tests listed no suite:\n${listing}")
endif()
string(APPEND content "set(ashlar_unit_suites [==[${suites}]==])\n")
file(WRITE ${OUTPUT}.new "${content}")
file(RENAME ${OUTPUT}.new ${OUTPUT})
