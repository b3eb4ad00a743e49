// A run's results directory (io::OutputDir::for_run): a manifest of what the run wrote, an earlier
// run's outputs replaced completely, other files never mixed in.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <cerrno>
#include <fcntl.h>
#include <unistd.h>

#include "jellysim/core/errors.hpp"
#include "jellysim/io/output.hpp"

namespace jellysim::io {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("jellysim_output_dir_" + name);
  fs::remove_all(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void touch(const fs::path& p) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << "x";
}

TEST(OutputDir, ListsEveryFileOfTheRunInItsManifestSorted) {
  const fs::path dir = fresh("manifest");
  const OutputDir out = OutputDir::for_run(dir, "test");
  out.write_text("b.csv", "1\n");
  out.subdirectory("frames").write_text("f_0001.png", "p");
  out.subdirectory("frames").write_text("f_0000.png", "p");
  out.write_text("a.json", "{}");
  out.write_text("b.csv", "2\n");  // rewritten: listed once
  // While the run goes on the manifest grows in writing order (a killed run still leaves it right).
  EXPECT_EQ(slurp(dir / kManifestName).substr(slurp(dir / kManifestName).find('\n') + 1),
            "b.csv\nframes/f_0001.png\nframes/f_0000.png\na.json\n");
  out.finish_manifest();
  const std::string text = slurp(dir / kManifestName);
  EXPECT_EQ(text, "# jellysim test: the files of this run; a later run into this directory removes them first\n"
                  "a.json\nb.csv\nframes/f_0000.png\nframes/f_0001.png\n");
  fs::remove_all(dir);
}

TEST(OutputDir, ALaterRunReplacesTheEarlierRunsOutputsCompletely) {
  const fs::path dir = fresh("replace");
  {
    const OutputDir first = OutputDir::for_run(dir, "test");
    for (int k = 0; k < 5; ++k) first.subdirectory("frames").write_text("f_" + std::to_string(k) + ".png", "p");
    first.subdirectory("meshes").write_text("m.obj", "o");
    first.write_text("summary.json", "{\"frames\": 5}");
    first.finish_manifest();
  }
  touch(dir / "frames" / "f_9.png.tmp-4242");           // temporaries killed runs left: this version's
  touch(dir / "frames" / "f_8.png.tmp-4242-2x9kq0f3");  // names and earlier versions'
  touch(dir / "f.png.tmp-42-");                         // not ours: a foreign file
  EXPECT_THROW(OutputDir::for_run(dir, "test"), InputError);
  fs::remove(dir / "f.png.tmp-42-");
  const OutputDir second = OutputDir::for_run(dir, "test");
  EXPECT_FALSE(fs::exists(dir / "frames"));  // emptied, so removed
  EXPECT_FALSE(fs::exists(dir / "meshes"));
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  second.subdirectory("frames").write_text("f_0.png", "p");
  second.write_text("summary.json", "{\"frames\": 1}");
  second.finish_manifest();
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    files += e.is_regular_file() && e.path().filename() != kLockName ? 1 : 0;  // the lock: while `second` lives
  EXPECT_EQ(files, 3);  // manifest, summary, one frame
  fs::remove_all(dir);
}

TEST(OutputDir, RefusesADirectoryWithFilesItDidNotWriteAndTouchesNothing) {
  const fs::path dir = fresh("foreign");
  {
    const OutputDir first = OutputDir::for_run(dir, "test");
    first.write_text("metrics.csv", "t\n");
    first.finish_manifest();
  }
  touch(dir / "notes" / "mine.txt");
  try {
    OutputDir::for_run(dir, "test");
    ADD_FAILURE() << "a directory with someone else's file was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("notes/mine.txt"), std::string::npos) << what;
    EXPECT_NE(what.find("new or empty directory"), std::string::npos) << what;
  }
  EXPECT_TRUE(fs::exists(dir / "metrics.csv"));  // nothing removed
  EXPECT_TRUE(fs::exists(dir / "notes" / "mine.txt"));

  const fs::path plain = fresh("plain");
  touch(plain / "thesis.pdf");  // not empty and no manifest: not ours
  EXPECT_THROW(OutputDir::for_run(plain, "test"), InputError);
  EXPECT_TRUE(fs::exists(plain / "thesis.pdf"));
  touch(fresh("file") );
  EXPECT_THROW(OutputDir::for_run(fs::temp_directory_path() / "jellysim_output_dir_file", "test"), InputError);
  fs::remove_all(dir);
  fs::remove_all(plain);
  fs::remove(fs::temp_directory_path() / "jellysim_output_dir_file");
}

TEST(OutputDir, AcceptsANewOrEmptyDirectory) {
  const fs::path dir = fresh("empty");
  fs::create_directories(dir);
  EXPECT_NO_THROW(OutputDir::for_run(dir, "test"));
  EXPECT_NO_THROW(OutputDir::for_run(fresh("new") / "nested", "test"));
  fs::remove_all(dir);
  fs::remove_all(fresh("new"));
}

// Issue 35 item 4: a run holds its directory for its life; a second run there is refused, naming the
// holder's pid, and the lock goes with the run.
TEST(OutputDir, ADirectoryIsLockedWhileItsRunLives) {
  const fs::path dir = fresh("locked");
  {
    const OutputDir first = OutputDir::for_run(dir, "test");
    const OutputDir frames = first.subdirectory("frames");
    try {
      OutputDir::for_run(dir, "test");
      ADD_FAILURE() << "a second run into a locked directory was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("in use by another jellysim run (pid " + std::to_string(::getpid()) + ")"),
                std::string::npos) << e.what();
    }
    EXPECT_THROW(OutputDir::for_resumed_run(dir, "test"), InputError);
  }
  EXPECT_FALSE(fs::exists(dir / kLockName));
  EXPECT_NO_THROW(OutputDir::for_run(dir, "test"));
  fs::remove_all(dir);
}

// Issue 35 item 3: the run's id is in its manifest while it goes on, kept by a resumed run, and gone
// from a whole run's manifest (the same bytes every time).
TEST(OutputDir, TheRunIdIsInTheManifestWhileTheRunCanBeResumed) {
  const fs::path dir = fresh("run_id");
  std::string id;
  {
    const OutputDir out = OutputDir::for_run(dir, "test");
    id = out.run_id();
    EXPECT_EQ(id.size(), 32u);
    EXPECT_EQ(manifest_run_id(dir), id);
    out.finish_manifest(true);
    EXPECT_EQ(manifest_run_id(dir), id);
  }
  {
    const OutputDir resumed = OutputDir::for_resumed_run(dir, "test");
    EXPECT_EQ(resumed.run_id(), id);
    resumed.finish_manifest();
    EXPECT_EQ(manifest_run_id(dir), "");
  }
  EXPECT_NE(OutputDir::for_run(dir, "test").run_id(), id);
  fs::remove_all(dir);
}

TEST(SafeFiles, TemporariesAreNewUnpredictableRegularFiles) {
  const fs::path dir = fresh("temporaries");
  const OutputDir out(dir);
  {
    const PendingFile a = out.temporary_for("frame.png");
    const PendingFile b = out.temporary_for("frame.png");
    EXPECT_NE(a.path(), b.path());
    for (const PendingFile* f : {&a, &b}) {
      const fs::path& p = f->path();
      EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(p))) << p;
      EXPECT_EQ(fs::file_size(p), 0u);
      EXPECT_EQ(p.filename().string().rfind("frame.png.tmp-" + std::to_string(::getpid()) + "-", 0), 0u) << p;
      EXPECT_GE(f->fd(), 0);  // open: the writer writes through it
    }
  }
  EXPECT_TRUE(fs::is_empty(dir));  // not committed: removed
  fs::remove_all(dir);
}

// A file is written through the descriptor its temporary was made with, never reopened by name:
// a symlink planted at the temporary's name between its creation and the write is not followed,
// and not moved into place (issue 35, item 13).
TEST(SafeFiles, ASymlinkPlantedAtATemporaryIsNeverWrittenThrough) {
  const fs::path dir = fresh("planted_temporary");
  const fs::path victim = fresh("planted_victim");
  fs::create_directories(victim);
  std::ofstream(victim / "precious.txt") << "keep";
  const OutputDir out = OutputDir::for_run(dir, "test");
  PendingFile file = out.temporary_for("frame.png");
  fs::remove(file.path());
  fs::create_symlink(victim / "precious.txt", file.path());
  write_all(file.fd(), "pixels", out.file("frame.png"));
  EXPECT_THROW(file.commit(), RunError);
  EXPECT_EQ(slurp(victim / "precious.txt"), "keep");
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "frame.png")));
  // Committed unharmed, the file holds what was written through the descriptor.
  PendingFile good = out.temporary_for("frame.png");
  write_all(good.fd(), "pixels", out.file("frame.png"));
  good.commit();
  EXPECT_EQ(slurp(dir / "frame.png"), "pixels");
  EXPECT_NE(slurp(dir / kManifestName).find("frame.png\n"), std::string::npos);
  fs::remove_all(dir);
  fs::remove_all(victim);
}

TEST(SafeFiles, APlantedSymlinkIsReplacedNeverWrittenThrough) {
  const fs::path dir = fresh("symlink");
  const OutputDir out(dir);
  const fs::path victim = fresh("symlink_victim");
  fs::create_directories(victim);
  std::ofstream(victim / "precious.txt") << "keep";
  fs::create_symlink(victim / "precious.txt", dir / "summary.json");
  out.write_text("summary.json", "{}\n");
  EXPECT_EQ(slurp(victim / "precious.txt"), "keep");
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / "summary.json")));
  EXPECT_EQ(slurp(dir / "summary.json"), "{}\n");
  fs::remove_all(dir);
  fs::remove_all(victim);
}

TEST(SafeFiles, AWriteErrorNamesThePathAndTheOperatingSystemsReason) {
  // /dev/full fails every write with ENOSPC, as a full disk does.
  const int fd = ::open("/dev/full", O_WRONLY);
  ASSERT_GE(fd, 0);
  try {
    write_all(fd, "data", "/results/metrics.csv");
    FAIL() << "a write to /dev/full succeeded";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("'/results/metrics.csv'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(os_reason(ENOSPC)), std::string::npos) << e.what();
  }
  ::close(fd);
  // A directory that does not exist: the reason is given too.
  try {
    write_file_atomically("/nonexistent-jellysim-dir/a.txt", "x");
    FAIL();
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find(os_reason(ENOENT)), std::string::npos) << e.what();
  }
}

// The log of the ffmpeg that earlier versions wrote beside a video's temporary is a temporary too:
// a run killed while encoding left it, and it must not block the directory (issue 35, item 6).
TEST(OutputDir, AKilledEncodersLogIsALeftoverTemporary) {
  const fs::path dir = fresh("ffmpeg_log");
  OutputDir::for_run(dir, "test").write_text("summary.json", "{}\n");
  touch(dir / "jellyfish.mp4.tmp-4242-2x9kq0f3");
  touch(dir / "jellyfish.mp4.tmp-4242-2x9kq0f3.ffmpeg-log");
  touch(dir / "jellyfish.mp4.tmp-4242.ffmpeg-log");
  EXPECT_NO_THROW(OutputDir::for_resumed_run(dir, "test"));
  EXPECT_FALSE(fs::exists(dir / "jellyfish.mp4.tmp-4242-2x9kq0f3.ffmpeg-log"));
  touch(dir / "jellyfish.mp4.tmp-4242-2x9kq0f3.ffmpeg-log");
  EXPECT_NO_THROW(OutputDir::for_run(dir, "test"));
  EXPECT_TRUE(fs::is_empty(dir) || fs::exists(dir / kManifestName));
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename(), kManifestName) << e.path();
  touch(dir / "notes.ffmpeg-log");  // not a temporary of ours
  EXPECT_THROW(OutputDir::for_run(dir, "test"), InputError);
  fs::remove_all(dir);
}

// The reason given is that of the call that failed: a rename refused (the target is a directory)
// is not reported as the "Success" of the clean-up after it (issue 35, item 12).
TEST(SafeFiles, AFailedRenameReportsItsOwnReason) {
  const fs::path dir = fresh("rename_reason");
  fs::create_directories(dir / "summary.json" / "inside");
  for (int k = 0; k < 2; ++k) {
    try {
      if (k == 0) write_file_atomically(dir / "summary.json", "{}");
      else OutputDir(dir).write_text("summary.json", "{}");
      FAIL() << "a file replaced a directory";
    } catch (const RunError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find(os_reason(0)), std::string::npos) << what;
      EXPECT_TRUE(what.find(os_reason(EISDIR)) != std::string::npos ||
                  what.find(os_reason(ENOTEMPTY)) != std::string::npos || what.find(os_reason(EEXIST)) != std::string::npos)
          << what;
    }
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // no temporary left
  fs::remove_all(dir);
}

}  // namespace
}  // namespace jellysim::io
