// Helpers of the cohort tests: a BIDS tree of small subjects, Snakemake and make runs, and their outputs compared.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "tests/support/cli.h"

namespace tissuemesh::testing {

/// data/workflows/snakemake and its Snakefile.
std::filesystem::path snakemake_folder();

/// A BIDS tree under `root`: sub-01 the junction phantom at 4 mm, sub-02 boxes at 4 mm, sub-03 the usc19-5 head
/// resampled to 8 mm, each as sub-XX/anat/sub-XX_dseg.nii.gz with its names in sub-XX_dseg.tsv (BIDS look-up table).
/// Meshed with cohort_config(): about 12 s of CPU for the three (2026-12-04, Release).
void make_bids_cohort(const std::filesystem::path& root);

/// Flags that keep the cohort small (8 mm edges, one refinement round), for Snakemake (--config) and for make.
std::vector<std::string> cohort_config();
std::vector<std::string> cohort_make_variables();

/// Adds sub-04 whose image is a truncated gzip stream (its names are fine), and sub-05 whose image is fine but whose
/// dseg.tsv has no name column.
void add_broken_subject(const std::filesystem::path& root);

/// snakemake -s Snakefile with `args`, after `environment` (NAME=VALUE) settings, started in `folder` (where
/// Snakemake keeps its own log, .snakemake/log).
CliResult run_snakemake(const std::filesystem::path& folder, const std::vector<std::string>& args,
                        const std::vector<std::string>& environment = {});

/// make -C data/workflows for one subject as the Snakefile ran it: IMAGE, LABELS, OUT and `extra` variables.
CliResult run_make(const std::filesystem::path& image, const std::filesystem::path& labels,
                   const std::filesystem::path& out, const std::vector<std::string>& extra = {});

/// The files a step writes besides its --json summary, the report page and refine.csv (they hold times), by name,
/// in `folder` (params/ and other folders left out).
std::vector<std::string> model_files(const std::filesystem::path& folder);

/// Whether two files hold the same bytes.
bool same_bytes(const std::filesystem::path& a, const std::filesystem::path& b);

/// A CSV file with a header line: one map per row (quoted fields, "" inside quotes).
std::vector<std::map<std::string, std::string>> read_csv(const std::filesystem::path& path);

/// Modification times of every .json file under `folder`, by path.
std::map<std::string, std::filesystem::file_time_type> json_times(const std::filesystem::path& folder);

/// Words of a shell command line (single and double quotes, no expansions): to compare command lines.
std::vector<std::string> shell_words(const std::string& line);

} // namespace tissuemesh::testing
