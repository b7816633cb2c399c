// The gallery page as people see it: `glint gallery` renders a few variants, and a headless
// Chromium (Debian's chromium; scripts/setup --test) loads the page from a fresh profile.
//
// How it is driven: a copy of index.html beside it (so the pictures load by the same
// relative paths) gets two scripts: one first thing in <head> that records every console
// error or warning, uncaught exception and resource that failed to load, and one at the
// end that decodes every picture, types into the filter box, and writes what it saw into
// the page. `chromium --headless --dump-dom` prints the page after its load event, and
// the test reads the facts from that dump and checks them here, against gallery.json.
// Chromium's own console log (--enable-logging=stderr) is a second net for console
// messages. One process, a file in and a page out: no DevTools connection to manage, no
// packages beyond chromium (the DevTools protocol would need python3-websockets, and an
// asynchronous check under --virtual-time-budget is printed before off-thread image
// decodes finish: virtual time runs ahead of them).
#include "support/cli.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using glint::testing::freshDir;
using glint::testing::readBytes;
using glint::testing::runGlint;
using glint::testing::runShell;
using glint::testing::shellQuote;

namespace {
// Recorded before the page's own markup and script run.
constexpr const char* kRecorder = R"(<script>
window.glintProblems = [];
for (const level of ['error', 'warn']) {
  const original = console[level];
  console[level] = (...args) => { glintProblems.push(`console.${level}: ${args.join(' ')}`); original.apply(console, args); };
}
window.addEventListener('error', (e) => glintProblems.push(e.target === window || !e.target.tagName
    ? `uncaught: ${e.message} (${e.filename}:${e.lineno})` : `failed to load: ${e.target.src || e.target.href}`), true);
window.addEventListener('unhandledrejection', (e) => glintProblems.push(`unhandled rejection: ${e.reason}`));
</script>)";

// Runs on the page's load event, which waits for every (eager) picture: each picture drawn
// into a canvas (drawImage decodes it, and throws for a broken one), then the filter box
// typed into like a user does (execCommand: real input events), then cleared. All of it
// synchronous, so the page is complete when --dump-dom prints it. The result goes into
// <pre id=glint-check> as URI-encoded JSON.
std::string checker(const std::string& filter) {
  return R"(<script>
window.addEventListener('load', () => {
  const result = {images: [], filtered: [], cleared: [], sections: []};
  const canvas = document.createElement('canvas').getContext('2d');
  for (const img of document.querySelectorAll('figure img')) {
    try {
      canvas.drawImage(img, 0, 0);
    } catch (e) {
      glintProblems.push(`cannot decode ${img.src}: ${e}`);
    }
    result.images.push({src: img.getAttribute('src'), width: img.naturalWidth, height: img.naturalHeight});
  }
  const visible = (selector) => [...document.querySelectorAll(selector)].filter((e) => e.checkVisibility());
  const box = document.getElementById('filter');
  if (box) {
    box.focus();
    document.execCommand('insertText', false, )" +
         nlohmann::json(filter).dump() + R"();
    result.filtered = visible('figure').map((f) => f.dataset.name);
    result.sections = visible('section h2').map((h) => h.id);
    result.links = visible('nav a').map((a) => a.getAttribute('href').slice(1));
    box.select();
    document.execCommand('delete');
    result.cleared = visible('figure').map((f) => f.dataset.name);
  } else {
    result.noFilterBox = true;
  }
  result.problems = glintProblems;
  const out = document.createElement('pre');
  out.id = 'glint-check';
  out.textContent = encodeURIComponent(JSON.stringify(result));
  document.body.append(out);
});
</script>)";
}

std::string decodeUri(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size()) {
      out += char(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

std::vector<std::string> strings(const nlohmann::json& array) { return array.get<std::vector<std::string>>(); }
}  // namespace

TEST(GalleryPage, LoadsInChromiumWithEveryPictureAtItsSizeAWorkingFilterAndNoConsoleErrors) {
  const fs::path dir = freshDir("gallery_page", "chromium");
  const fs::path gallery = dir / "gallery";
  // Three scenes, 16 variants, small and not square (a width and height swapped shows).
  const auto render = runGlint("-q gallery --filter basics/ --size 160x96 --repeats 0 -o " + shellQuote(gallery));
  ASSERT_EQ(render.status, 0) << render.output;
  const auto manifest = nlohmann::json::parse(readBytes(gallery / "gallery.json"));
  const auto& variants = manifest.at("variants");
  ASSERT_GE(variants.size(), 4u);

  // The page with the recorder and the checker added, beside the original.
  std::string page = readBytes(gallery / "index.html");
  const std::string charset = "<meta charset=utf-8>";
  const auto head = page.find(charset);
  ASSERT_NE(head, std::string::npos) << "index.html has no " << charset;
  page.insert(head + charset.size(), kRecorder);
  const std::string filter = "triangle/";
  const auto end = page.rfind("</body>");
  ASSERT_NE(end, std::string::npos);
  page.insert(end, checker(filter));
  // Headless Chromium never scrolls, so pictures below the first screen would never start
  // loading: the copy loads them all at once (what is checked is the pictures, not when
  // they load).
  const std::string lazy = " loading=lazy";
  ASSERT_NE(page.find(lazy), std::string::npos);
  for (auto at = page.find(lazy); at != std::string::npos; at = page.find(lazy, at)) page.replace(at, lazy.size(), "");
  std::ofstream(gallery / "checked.html") << page;

  // A fresh Chromium: its own profile, home and caches; no display, no GPU, and no
  // sandbox (the tests may run as root, where Chromium's sandbox refuses to start).
  const fs::path home = dir / "home";
  const auto browser = runShell(fmt::format(
      "(HOME={0} XDG_CONFIG_HOME={0}/config XDG_CACHE_HOME={0}/cache timeout 120 chromium --headless --no-sandbox "
      "--disable-gpu --no-first-run --user-data-dir={1} --enable-logging=stderr --v=0 --virtual-time-budget=10000 "
      "--dump-dom {2} > {3} 2> {4})",
      shellQuote(home), shellQuote(dir / "profile"), shellQuote("file://" + (gallery / "checked.html").string()),
      shellQuote(dir / "dom.html"), shellQuote(dir / "chromium.log")));
  ASSERT_EQ(browser.status, 0) << browser.output << readBytes(dir / "chromium.log")
                               << (browser.status == 127 ? "\nchromium is missing: scripts/setup --test installs it" : "");
  const std::string dom = readBytes(dir / "dom.html");
  const std::string open = "<pre id=\"glint-check\">";
  const auto at = dom.find(open);
  ASSERT_NE(at, std::string::npos) << "the checks did not finish; Chromium's log:\n" << readBytes(dir / "chromium.log");
  const auto result = nlohmann::json::parse(decodeUri(dom.substr(at + open.size(), dom.find("</pre>", at) - at - open.size())));

  // Every picture decodes at the size gallery.json records for it.
  ASSERT_FALSE(result.value("noFilterBox", false)) << "the page has no filter box (#filter)";
  std::vector<std::string> names;
  for (const auto& v : variants) {
    names.push_back(v.at("name"));
    const auto shown = std::find_if(result.at("images").begin(), result.at("images").end(),
                                    [&](const auto& img) { return img.at("src") == v.at("image"); });
    ASSERT_NE(shown, result.at("images").end()) << v.at("image") << " is not on the page";
    EXPECT_EQ(v.at("width"), 160) << v.at("name");
    EXPECT_EQ(v.at("height"), 96) << v.at("name");
    EXPECT_EQ(shown->at("width"), v.at("width")) << v.at("image");
    EXPECT_EQ(shown->at("height"), v.at("height")) << v.at("image");
  }
  EXPECT_EQ(result.at("images").size(), variants.size());

  // Typing a filter shows exactly the variants whose names contain it, and the sections
  // and contents links of their scenes only; clearing it shows everything again.
  std::vector<std::string> matching;
  std::set<std::string> scenes;
  for (const auto& name : names) {
    if (name.find(filter) == std::string::npos) continue;
    matching.push_back(name);
    scenes.insert(name.substr(0, name.rfind('/')));
  }
  ASSERT_FALSE(matching.empty());
  ASSERT_LT(matching.size(), names.size()) << "the filter must hide something to be tested";
  EXPECT_EQ(strings(result.at("filtered")), matching);
  EXPECT_EQ(std::set<std::string>(result.at("sections").begin(), result.at("sections").end()), scenes);
  EXPECT_EQ(std::set<std::string>(result.at("links").begin(), result.at("links").end()), scenes);
  EXPECT_EQ(strings(result.at("cleared")), names);

  // No console errors or warnings, no uncaught exceptions, nothing that failed to load:
  // as the page recorded them, and as Chromium logged its console.
  EXPECT_TRUE(result.at("problems").empty()) << result.at("problems").dump(1);
  std::istringstream log(readBytes(dir / "chromium.log"));
  for (std::string line; std::getline(log, line);) {
    EXPECT_EQ(line.find(":CONSOLE"), std::string::npos) << line;
  }
}
