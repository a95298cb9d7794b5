// `ladarsim campaign`: a spec of distributions into many reproducible sequences, resumable and in
// shards (docs/campaign.md).
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "command.h"
#include "ladarsim/campaign/campaign_run.h"
#include "ladarsim/campaign/campaign_spec.h"
#include "ladarsim/core/input_error.h"
#include "option_checks.h"
#include "plot_script.h"
#include "progress.h"
#include "stop_signal.h"

namespace ladarsim::apps {
namespace {

/// "I/N" with 0 <= I < N.
CLI::Validator shard_option() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            int i = -1, n = 0;
            char extra = 0;
            if (std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &extra) != 2 || n < 1 || i < 0 || i >= n)
                return "'" + text + "' is not a shard I/N with 0 <= I < N";
            return {};
        },
        "I/N");
}

/// "3/8 sequences, sequence 000004 frame 2/4, 1.7 frames/s, about 12 s left".
std::string progress_text(const campaign::CampaignProgress& p) {
    char text[256];
    const double rate = p.seconds > 0.0 ? p.frames_rendered / p.seconds : 0.0;
    const std::string left = rate > 0.0 ? "about " + std::to_string(static_cast<long long>(p.frames_left / rate + 0.5)) + " s left"
                                        : "time left unknown";
    std::snprintf(text, sizeof text, "campaign: %d/%d sequences, sequence %06d frame %d/%d, %.1f frames/s, %s",
                  p.sequences_done, p.sequences_in_share, p.sequence, p.frame, p.frames, rate, left.c_str());
    return text;
}

struct CampaignCommand {
    std::string spec_file, out_dir, shard = "0/1";
    int sequences = 0, frames = 0, threads = 0;
    std::uint64_t seed = 0;
    long long stop_after_frames = -1;
    bool quiet = false;
    CLI::App* command = nullptr;

    CLI::App* add(CLI::App& app) {
        command = app.add_subcommand(
            "campaign",
            "Render a dataset campaign: many sequences, each a dataset drawn from the spec's distributions\n"
            "(docs/campaign.md), with campaign.json indexing them by split and card.md summing them up.\n"
            "Run it again to resume; --shard I/N renders a disjoint share into the same directory");
        command->add_option("spec", spec_file, "Campaign spec (JSON, see docs/campaign.md)")->required();
        command->add_option("--out", out_dir, "Campaign directory: absent, empty or this campaign's (it resumes)")->required();
        command->add_option("--sequences", sequences, "Number of sequences (default: the spec's sequences)")
            ->check(whole_number(1, 10'000'000));
        command->add_option("--frames", frames, "Frames per sequence (default: the spec's frames)")
            ->check(whole_number(1, 10'000'000));
        command->add_option("--seed", seed, "Campaign seed (default: the spec's seed)")
            ->check(whole_number(0, std::numeric_limits<long long>::max()));
        command->add_option("--shard", shard, "Render the I-th of N disjoint shares (sequences i with i mod N = I)")
            ->check(shard_option());
        command->add_option("--threads", threads, "Worker threads (default: all cores); output does not depend on it")
            ->check(whole_number(0, std::numeric_limits<int>::max()));
        command->add_flag("--quiet", quiet, "No progress output");
        command->add_option("--stop-after-frames", stop_after_frames, "For testing: stop as Ctrl-C would after this many frames");
        return command;
    }

    int run() {
        campaign::SpecOverrides overrides;
        if (command->count("--sequences")) overrides.sequences = sequences;
        if (command->count("--frames")) overrides.frames = frames;
        if (command->count("--seed")) overrides.seed = seed;
        const campaign::CampaignSpec spec = campaign::read_campaign_spec(spec_file, overrides);

        campaign::CampaignOptions options;
        options.out_dir = out_dir;
        std::sscanf(shard.c_str(), "%d/%d", &options.shard, &options.shards);
        options.threads = threads;
        options.stop = &g_stop;
        std::signal(SIGINT, request_stop);
        std::signal(SIGTERM, request_stop);
        const bool terminal = stderr_is_terminal();
        options.progress = [&](const campaign::CampaignProgress& p) {
            if (stop_after_frames >= 0 && p.frames_rendered >= stop_after_frames) g_stop = true;
            if (quiet) return;
            // Elsewhere than a terminal, one line per finished sequence.
            if (terminal) std::fprintf(stderr, "\r%s", progress_text(p).c_str());
            else if (p.frame == p.frames) std::fprintf(stderr, "%s\n", progress_text(p).c_str());
        };
        const campaign::CampaignSummary s = campaign::run_campaign(spec, options);
        if (!quiet && terminal && s.frames_rendered > 0) std::fprintf(stderr, "\n");
        const std::string out = s.out_dir.string();
        if (s.interrupted) {
            std::fprintf(stderr, "interrupted after %d sequences; run the same command again to continue\n", s.rendered);
            return 130;
        }
        std::printf("rendered %d sequences (%lld frames) into %s in %.1f s", s.rendered, s.frames_rendered, out.c_str(), s.seconds);
        if (s.already_done > 0) std::printf("; %d of this share were already there", s.already_done);
        std::printf("\n");
        if (s.index_written) {
            std::printf("wrote %s/campaign.json: %d sequences of %d frames\n", out.c_str(), spec.sequences, spec.frames);
            run_plot_script("plot_campaign.py", {out + "/campaign.json", out + "/card.md"});
            std::printf("wrote %s/card.md, the dataset card, and its plots card-*.png\n", out.c_str());
        } else {
            std::printf("%d of the campaign's %d sequences are finished; campaign.json is written by the run that "
                        "finishes the last\n",
                        s.campaign_done, spec.sequences);
        }
        return 0;
    }
};

}  // namespace

void add_campaign_command(CLI::App& app, int& exit_code) {
    add_command(app, std::make_shared<CampaignCommand>(), exit_code);
}

}  // namespace ladarsim::apps
