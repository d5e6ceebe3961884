// `seqc beats` in-process on fake audio (no song files; the beat list goes to a temporary
// folder): what it prints for a song whose tempo map is known from how it was made, and the exit
// status and wording of each failure.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "compiler/compile.hpp"

#include "runtime/cli/beats_command.hpp"
#include "runtime/io/clock.hpp"
#include "tests/music/song_generator.hpp"

namespace seqc::cli {
namespace {

class NoFiles final : public seqc::FileReader {
 public:
  Result<std::string> read(const std::string& path) override {
    return make_error(path + ": not here");
  }
};

class FakeReader final : public audio::AudioReader {
 public:
  explicit FakeReader(Result<audio::MonoAudio> song) : song_(std::move(song)) {}
  Result<audio::MonoAudio> read(const std::string& path) override {
    paths.push_back(path);
    return song_;
  }
  std::vector<std::string> paths;

 private:
  Result<audio::MonoAudio> song_;
};

class FakeWriter final : public audio::AudioWriter {
 public:
  Status write_wav(const std::string& path, const audio::MonoAudio& audio) override {
    written_path = path;
    written = audio;
    if (fail) return make_error(path + ": cannot write: disk full");
    return Ok{};
  }
  std::string written_path;
  audio::MonoAudio written;
  bool fail = false;
};

struct CommandRun {
  std::ostringstream out, err;
  io::ManualClock clock;
  NoFiles files;
  Context ctx{out, err, clock, files};
};

audio::MonoAudio clicks(double tempo, double lead_in_s) {
  const testing::Song song = testing::make_clicks(tempo, 4, lead_in_s, 20, 16000);
  return {song.samples, song.sample_rate};
}

TEST(BeatsCommand, PrintsTheMusicBlockAndWritesTheClickTrack) {
  // 120 BPM clicks from 0.5 s, every 4th accented: exact, so the fit is to the thousandth and
  // 120.000 prints as 120.
  FakeReader reader(clicks(120, 0.5));
  FakeWriter writer;
  CommandRun run;
  BeatsRequest request{"songs/clicks.ogg", std::nullopt, std::nullopt, "out.wav", std::nullopt};
  EXPECT_EQ(run_beats(run.ctx, request, reader, writer), ExitCode::Ok);
  EXPECT_EQ(reader.paths, std::vector<std::string>{"songs/clicks.ogg"});
  EXPECT_EQ(run.out.str(),
            "music:\n"
            "  file: songs/clicks.ogg\n"
            "  downbeat: 0.500s\n"
            "  tempo: 120\n"
            "  meter: 4/4\n");
  EXPECT_NE(run.err.str().find("seqc: songs/clicks.ogg: "), std::string::npos) << run.err.str();
  EXPECT_NE(run.err.str().find("confidence 1.00"), std::string::npos) << run.err.str();
  EXPECT_EQ(writer.written_path, "out.wav");
  EXPECT_EQ(writer.written.sample_rate, 16000);
  EXPECT_EQ(writer.written.samples.size(), std::size_t{20 * 16000});
}

TEST(BeatsCommand, QuietPrintsOnlyTheBlock) {
  FakeReader reader(clicks(100, 1.0));
  FakeWriter writer;
  CommandRun run;
  run.ctx.verbosity = -1;
  EXPECT_EQ(run_beats(run.ctx, {"c.wav", std::nullopt, std::nullopt, std::nullopt, std::nullopt},
                      reader, writer),
            ExitCode::Ok);
  EXPECT_EQ(run.err.str(), "");
  EXPECT_EQ(writer.written_path, "");  // no --click, nothing written
}

TEST(BeatsCommand, UnreadableSongIsAFileError) {
  FakeReader reader(make_error("gone.flac: no such file"));
  FakeWriter writer;
  CommandRun run;
  EXPECT_EQ(
      run_beats(run.ctx, {"gone.flac", std::nullopt, std::nullopt, std::nullopt, std::nullopt},
                reader, writer),
      ExitCode::FileError);
  EXPECT_EQ(run.out.str(), "");
  EXPECT_EQ(run.err.str(), "seqc: error: gone.flac: no such file\n");
}

TEST(BeatsCommand, NoSteadyBeatIsInvalidInputAndPrintsNoGuess) {
  const testing::Song noise = testing::make_noise(12, 0.1, 16000, 3);
  FakeReader reader(audio::MonoAudio{noise.samples, noise.sample_rate});
  FakeWriter writer;
  CommandRun run;
  EXPECT_EQ(run_beats(run.ctx, {"rain.wav", std::nullopt, std::nullopt, "c.wav", std::nullopt},
                      reader, writer),
            ExitCode::InvalidInput);
  EXPECT_EQ(run.out.str(), "");
  EXPECT_EQ(run.err.str().rfind("seqc: error: rain.wav: no steady beat found (", 0), 0u)
      << run.err.str();
  EXPECT_EQ(writer.written_path, "");
}

TEST(BeatsCommand, FailedClickWriteIsAFileError) {
  FakeReader reader(clicks(120, 0.5));
  FakeWriter writer;
  writer.fail = true;
  CommandRun run;
  EXPECT_EQ(run_beats(run.ctx, {"c.wav", std::nullopt, std::nullopt, "/full/out.wav", std::nullopt},
                      reader, writer),
            ExitCode::FileError);
  EXPECT_NE(run.err.str().find("seqc: error: /full/out.wav: cannot write: disk full\n"),
            std::string::npos)
      << run.err.str();
}

TEST(BeatsCommand, BeatsOutWritesEachBeatAndItsPlaceInTheBar) {
  // 120 BPM clicks from 0.5 s, every 4th accented: a beat every 0.5 s, bar 1 at 0.5 s.
  FakeReader reader(clicks(120, 0.5));
  FakeWriter writer;
  CommandRun run;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("seqc-beats-out-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string out = (dir / "song.beats").string();
  EXPECT_EQ(
      run_beats(run.ctx, {"c.wav", std::nullopt, std::nullopt, std::nullopt, out}, reader, writer),
      ExitCode::Ok);
  std::ifstream in(out);
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(first, "0.500\t1");
  EXPECT_EQ(second, "1.000\t2");
  // The song itself is never the list's destination.
  CommandRun again;
  EXPECT_EQ(
      run_beats(again.ctx, {out, std::nullopt, std::nullopt, std::nullopt, out}, reader, writer),
      ExitCode::Usage);
  EXPECT_NE(again.err.str().find("--beats-out " + out + " is the same file as the input"),
            std::string::npos)
      << again.err.str();
  std::filesystem::remove_all(dir);
}

// A choreography and its song from memory, for the round trip below.
class OneDance final : public seqc::FileReader {
 public:
  std::map<std::string, std::string> texts;
  testing::Song song;
  Result<std::string> read(const std::string& path) override {
    auto it = texts.find(path);
    if (it == texts.end()) return make_error(path + ": not here");
    return it->second;
  }
};
class DanceSongs final : public seqc::SongReader {
 public:
  explicit DanceSongs(OneDance& d) : d_(d) {}
  Result<seqc::SongSamples> read(const std::string&) override {
    return seqc::SongSamples{d_.song.samples, d_.song.sample_rate};
  }

 private:
  OneDance& d_;
};

// The line of `block` after "KEY: ", without its unit ("0.610s" -> 0.610).
double value_of(const std::string& block, const std::string& key) {
  const auto at = block.find("  " + key + ": ");
  return std::stod(block.substr(at + key.size() + 4));
}

TEST(BeatsCommand, TheClickTrackIsThePrintedMapAndTheCheckFindsNoDriftOnIt) {
  // A song at 123 bpm from 0.61 s, 24 bars. `seqc beats` prints a block; every click of its
  // click track starts on that block's beats (downbeat + k x 60 / tempo, reckoned here from
  // the printed text), and a choreography with that block checks quietly against the song.
  testing::SongSpec spec;
  spec.tempo = 123;
  spec.lead_in_s = 0.61;
  spec.bars = 24;
  OneDance dance;
  dance.song = testing::make_song(spec);
  FakeReader reader(audio::MonoAudio{dance.song.samples, dance.song.sample_rate});
  FakeWriter writer;
  CommandRun run;
  BeatsRequest request{"music/song.wav", std::nullopt, std::nullopt, "click.wav", std::nullopt};
  ASSERT_EQ(run_beats(run.ctx, request, reader, writer), ExitCode::Ok) << run.err.str();
  const std::string block = run.out.str();
  ASSERT_EQ(block.find("changes"), std::string::npos) << block;
  const double downbeat = value_of(block, "downbeat");
  const double period = 60 / value_of(block, "tempo");

  // The clicks alone: the mix less the song at 70%; each click's first sample above 0.01.
  const double rate = dance.song.sample_rate;
  std::vector<double> onsets;
  std::size_t quiet_until = 0;
  for (std::size_t i = 0; i < writer.written.samples.size(); ++i) {
    const double click = writer.written.samples[i] - 0.7 * dance.song.samples[i];
    if (i >= quiet_until && std::abs(click) > 0.01) {
      onsets.push_back(double(i) / rate);
      quiet_until = i + static_cast<std::size_t>(0.1 * rate);
    }
  }
  ASSERT_GT(onsets.size(), 24u * 4);
  for (double t : onsets) {
    const double k = std::round((t - downbeat) / period);
    EXPECT_NEAR(t, downbeat + k * period, 2.5 / rate) << "click at " << t << " s";
  }

  dance.texts["main.yaml"] = "robot: xarm\n" + block +
                             "sequence:\n  - move: home\n    time: 1bar\n"
                             "  - move: {base: 600}\n    time: 20bar\n";
  DanceSongs songs(dance);
  compiler::CompileOptions options;
  options.songs = &songs;
  const compiler::CompileOutput out = compiler::compile_file("main.yaml", dance, options);
  EXPECT_TRUE(out.program.has_value());
  std::vector<std::string> said;
  for (const seqc::Diagnostic& d : out.diagnostics.all()) said.push_back(d.message);
  EXPECT_EQ(said, std::vector<std::string>{});
}

}  // namespace
}  // namespace seqc::cli
