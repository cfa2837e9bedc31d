// tm-report: the workflow's pictures and --json summaries as one self-contained report.html.
#include "core/atomic_file.h"
#include "core/error.h"
#include "render/report_html.h"
#include "tools/run_tool.h"

using namespace tissuemesh;

int main(int argc, char** argv)
{
    std::string input, output, title = "tissuemesh run report";
    return tools::run_tool(
        argc, argv,
        {"tm-report",
         "Writes report.html from a workflow folder: every PNG in it (embedded, so the page opens anywhere), a table "
         "of "
         "tissues for every --json summary that has them (volumes, Dice, error volume, quality), and the steps with "
         "their "
         "status, time and peak memory, in pipeline order.",
         "Examples:\n  tm-report -i out/head -o out/head/report.html --title \"sphere head, 2 mm\""},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Workflow folder with the steps' --json summaries and PNG pictures")
                ->required();
            app.add_option("-o,--output", output, "The report (.html); default: INPUT/report.html");
            app.add_option("--title", title, "Page title")->capture_default_str();
        },
        [&](tools::ToolContext& context) {
            if (output.empty()) output = (std::filesystem::path(input) / "report.html").string();
            if (full_extension(output) != ".html")
                throw InputError(concat(output, ": the report must be an .html file"));
            render::ReportContent content = render::collect_report(input);
            content.title = title;
            // A summary of this very report (from an earlier run) is not a step of the workflow.
            std::erase_if(content.steps,
                          [](const render::ReportStep& s) { return s.summary.value("tool", "") == "tm-report"; });
            const std::string html = render::report_html(content);
            write_text_atomically(output, html);
            context.summary = {{"output", output},
                               {"steps", content.steps.size()},
                               {"pictures", content.pictures.size()},
                               {"bytes", html.size()}};
            context.log(concat(content.steps.size(), " steps, ", content.pictures.size(), " pictures -> ", output));
        });
}
