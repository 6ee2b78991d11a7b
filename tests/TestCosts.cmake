# Run by ctest, not cmake (tests/CMakeLists.txt adds it to TEST_INCLUDE_FILES after the
# gtest_discover_tests files, so the <program>_TESTS lists hold the test names this build found).
# Gives the tests whose names match a pattern of tmdem_test_costs (pairs: regular expression, COST)
# that COST, so that ctest -j starts the longest first. A fresh build has no cost data of its own
# (Testing/Temporary/CTestCostData.txt), and ctest then starts tests in the order they were added:
# the end-to-end, ParaView and validation tests last, one core left alone with them at the end.
# A pattern that matches nothing sets nothing (a renamed test simply loses its head start).
get_cmake_property(tmdem_variables VARIABLES)
list(FILTER tmdem_variables INCLUDE REGEX "^test_[a-z0-9_]+_TESTS$")
list(LENGTH tmdem_test_costs tmdem_pairs)
foreach(tmdem_list IN LISTS tmdem_variables)
  foreach(tmdem_test IN LISTS ${tmdem_list})
    set(tmdem_cost "")
    foreach(tmdem_i RANGE 0 ${tmdem_pairs} 2)
      if(tmdem_i LESS tmdem_pairs)
        list(GET tmdem_test_costs ${tmdem_i} tmdem_pattern)
        math(EXPR tmdem_j "${tmdem_i} + 1")
        if(tmdem_test MATCHES "${tmdem_pattern}" AND tmdem_cost STREQUAL "")
          list(GET tmdem_test_costs ${tmdem_j} tmdem_cost)
        endif()
      endif()
    endforeach()
    if(NOT tmdem_cost STREQUAL "")
      set_tests_properties("${tmdem_test}" PROPERTIES COST ${tmdem_cost})
    endif()
  endforeach()
endforeach()
