# seqc_studio_robot: the robot that follows the studio page's playhead (robot_follower.hpp),
# through the boards' live frames.
seqc_library(seqc_studio_robot
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/robot_follower.cpp
  DEPS seqc_boards Threads::Threads)
