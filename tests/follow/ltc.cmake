# SMPTE timecode: the signals are written at test time by libltc (ltc_signal.py, through
# Python's ctypes; libltc is never linked into seqc) into the build folder, a fixture every
# timecode test requires.
set(SEQC_LTC_DIR ${CMAKE_CURRENT_BINARY_DIR}/ltc-signals)
add_test(NAME ltc_signals
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/ltc_signal.py ${SEQC_LTC_DIR})
set_tests_properties(ltc_signals PROPERTIES FIXTURES_SETUP ltc_signals SKIP_RETURN_CODE 77)

# The timecode arithmetic, the decoder on libltc's signals, and the show clock on them through
# the WAV input on a manual clock.
add_executable(seqc_ltc_tests ltc_timecode_test.cpp ltc_decoder_test.cpp ltc_clock_test.cpp)
target_link_libraries(seqc_ltc_tests PRIVATE seqc_follow_ltc seqc_audio GTest::gtest GTest::gtest_main
                                             seqc_warnings)
target_include_directories(seqc_ltc_tests PRIVATE ${PROJECT_SOURCE_DIR})
target_compile_definitions(seqc_ltc_tests PRIVATE SEQC_LTC_DIR="${SEQC_LTC_DIR}")
gtest_discover_tests(seqc_ltc_tests DISCOVERY_MODE PRE_TEST
                     PROPERTIES FIXTURES_REQUIRED ltc_signals)

# The show clock on a real sound server: libltc's signal into a null sink, recorded from its
# monitor (with_pulse.sh starts PulseAudio when none runs); label `sound`, as tests/music's.
pkg_check_modules(LTC_PULSE_TEST QUIET IMPORTED_TARGET libpulse-simple libpulse)
add_executable(seqc_ltc_pulse_tests ltc_pulse_test.cpp)
target_link_libraries(seqc_ltc_pulse_tests PRIVATE seqc_follow_ltc seqc_audio
                                                   PkgConfig::LTC_PULSE_TEST Threads::Threads
                                                   GTest::gtest GTest::gtest_main seqc_warnings)
target_include_directories(seqc_ltc_pulse_tests PRIVATE ${PROJECT_SOURCE_DIR})
target_compile_definitions(seqc_ltc_pulse_tests PRIVATE SEQC_LTC_DIR="${SEQC_LTC_DIR}")
add_test(NAME ltc_pulse
         COMMAND ${PROJECT_SOURCE_DIR}/tests/music/with_pulse.sh
                 $<TARGET_FILE:seqc_ltc_pulse_tests>)
set_tests_properties(ltc_pulse PROPERTIES LABELS "sound" SKIP_RETURN_CODE 77 RUN_SERIAL TRUE
                                          FIXTURES_REQUIRED ltc_signals)

# The command line's half (runtime/cli/follow_ltc): its words and the clock it makes.
add_executable(seqc_ltc_cli_tests follow_ltc_cli_test.cpp)
target_link_libraries(seqc_ltc_cli_tests PRIVATE seqc_cli GTest::gtest GTest::gtest_main
                                                 seqc_warnings)
target_include_directories(seqc_ltc_cli_tests PRIVATE ${PROJECT_SOURCE_DIR})
target_compile_definitions(seqc_ltc_cli_tests PRIVATE SEQC_LTC_DIR="${SEQC_LTC_DIR}")
gtest_discover_tests(seqc_ltc_cli_tests DISCOVERY_MODE PRE_TEST
                     PROPERTIES FIXTURES_REQUIRED ltc_signals)

# `seqc follow --ltc` end to end: the arm (in-process emu:xarm) and the car (emu:raspblock)
# follow libltc's show signal read at its real pace from a WAV file.
add_test(NAME follow_ltc_wav
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/ltc_follow_test.py
                 $<TARGET_FILE:seqc> ${PROJECT_SOURCE_DIR} ${SEQC_LTC_DIR})
set_tests_properties(follow_ltc_wav PROPERTIES FIXTURES_REQUIRED ltc_signals SKIP_RETURN_CODE 77
                                               RUN_SERIAL TRUE TIMEOUT 120 LABELS "timed")
