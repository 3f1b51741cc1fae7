#pragma once
// Command lines of the examples, the benchmarks and the convergence tool, parsed by
// vtksys::CommandLineArguments: `--help` lists every flag, and a flag that is unknown, lacks its
// value or has a value that is not a number is an error.

#include <vtksys/CommandLineArguments.hxx>

#include <deque>
#include <string>
#include <vector>

namespace savr_scenes
{

class Arguments
{
public:
  /// `synopsis` heads the help: what the program does and how it is called.
  Arguments(int argc, char* argv[], std::string synopsis);

  ///@{
  /// A flag without a value sets `value` to true; an option sets `value` from the argument
  /// after it.
  void Flag(const char* name, bool* value, const char* help);
  void Option(const char* name, int* value, const char* help);
  void Option(const char* name, double* value, const char* help);
  void Option(const char* name, std::string* value, const char* help);
  ///@}
  /// The parser keeps only a pointer to a flag's help: a help text made on the fly is kept here.
  const char* Keep(std::string help);

  /// Accepts up to `count` arguments that are not flags, described in the help by `what`.
  void Positional(std::vector<std::string>* values, std::size_t count, const char* what);

  /// Parses the command line: true to go on; false when the program should end with
  /// ExitCode() (0 after --help, with the help printed; 1 after an error, with a message).
  bool Parse();
  int ExitCode() const { return this->Code; }

private:
  struct Number
  {
    Arguments* Owner;
    void* Value;
    bool Integer;
  };
  static int ParseNumber(const char* argument, const char* value, void* number);

  vtksys::CommandLineArguments Parser;
  std::vector<std::string> Given;
  std::string Synopsis;
  std::deque<Number> Numbers;
  std::deque<std::string> HelpTexts;
  std::vector<std::string>* PositionalValues = nullptr;
  std::size_t PositionalCount = 0;
  std::string PositionalHelp;
  std::string Error;
  bool Help = false;
  int Code = 0;
};

} // namespace savr_scenes
