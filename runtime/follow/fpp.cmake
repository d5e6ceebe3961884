# `seqc follow --fpp`: the FPP MultiSync ShowClock, and the follower that drives a robot from any
# ShowClock (show_clock.hpp).
seqc_library(seqc_follow_fpp
  SOURCES multisync_clock.cpp follower.cpp
  DEPS seqc_io seqc_protocol seqc_boards fmt::fmt)
