# Writes OUTPUT (conformance/build_commit.h) with the source tree's commit, at build time: run by the
# oceanref_build_commit target on every build, it rewrites the header only when the commit or
# the tree's clean/dirty state changed, so a rebuild with no change recompiles nothing.
#   cmake -DSOURCE_DIR=… -DOUTPUT=… -P build_commit.cmake
cmake_minimum_required(VERSION 3.18)  # file(CONFIGURE), current policies
set(commit "unknown")
execute_process(COMMAND git -C "${SOURCE_DIR}" rev-parse --short HEAD
                OUTPUT_VARIABLE head RESULT_VARIABLE head_status
                OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(head_status EQUAL 0 AND head)
  set(commit "${head}")
  # Tracked files differing from HEAD (staged or not); untracked files do not count.
  execute_process(COMMAND git -C "${SOURCE_DIR}" diff --quiet HEAD --
                  RESULT_VARIABLE dirty_status OUTPUT_QUIET ERROR_QUIET)
  if(NOT dirty_status EQUAL 0)
    set(commit "${commit}-dirty")
  endif()
endif()
file(CONFIGURE OUTPUT "${OUTPUT}"
     CONTENT "// Generated at build time by src/conformance/build_commit.cmake: the source tree's commit.\n#pragma once\n#define OCEANREF_COMMIT \"@commit@\"\n"
     @ONLY)
