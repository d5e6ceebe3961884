# seqc_follow_ltc: a show clock from SMPTE linear timecode heard on an audio input (ltc_clock),
# decoded by protocol/ltc_decoder.
seqc_library(seqc_follow_ltc
  SOURCES ltc_clock.cpp
  DEPS seqc_protocol seqc_audio seqc_io)
