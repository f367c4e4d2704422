// Where a command may write. Every command checks its outputs against its inputs before any work
// starts, so that a wrong path costs nothing and harms nothing:
//  - a file output never replaces a folder (the working directory included) or an input of the run;
//  - a folder output is written inside: ramap replaces only entries it writes itself (numbered
//    model folders holding nothing but model files, summary.json) and refuses anything else;
//  - the database is changed in place, keeping every table and row ramap does not own.
#pragma once

#include <string>
#include <vector>

namespace ramap {

// Throws InputError naming `option` and `path` when `path` is an existing folder, the same file as
// one of `inputs`, or has no file name ("." , "out/").
void CheckFileOutput(const std::string& option, const std::string& path,
                     const std::vector<std::string>& inputs);

// Throws InputError naming `option` and `path` when `path` exists and is not a folder, or is the
// same folder as one of `inputs` (e.g. a model converted onto itself).
void CheckFolderOutput(const std::string& option, const std::string& path,
                       const std::vector<std::string>& inputs);

// A model output of a command that transforms one model (bundle_adjuster, model_aligner): as
// COLMAP's, it may be the input folder itself (the model is read whole first; its files are then
// replaced by renames, other files in the folder left alone); otherwise as CheckFolderOutput.
void CheckModelOutputMayReplaceInput(const std::string& option, const std::string& path,
                                     const std::string& input_model,
                                     const std::vector<std::string>& other_inputs = {});

// A new database file: as CheckFileOutput, and it must not exist yet (the commands that create
// a database never overwrite one; `ramap matcher` is the one that changes a database in place).
void CheckNewDatabasePath(const std::string& option, const std::string& path,
                          const std::vector<std::string>& inputs);

// Whether `folder` holds only what a COLMAP model folder written by ramap or COLMAP holds (model
// files, trajectory, georeference), so that it may be replaced by a new model. Else `foreign` is
// set to the first other entry.
bool IsReplaceableModelFolder(const std::string& folder, std::string* foreign);

// Whether the page at `path` is a report.html that ramap wrote (its generator tag, in its first
// lines): a user's own report.html is never replaced.
bool IsRamapReport(const std::string& path);

// Whether `folder` holds only what a mapper's output folder holds (numbered replaceable model
// folders, summary.json, a report.html ramap wrote, COLMAP's project files), so that a rerun may
// replace it whole.
bool IsReplaceableMapperOutput(const std::string& folder, std::string* foreign);

}  // namespace ramap
