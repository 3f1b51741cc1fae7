#include "SAVRArguments.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>

namespace savr_scenes
{

Arguments::Arguments(int argc, char* argv[], std::string synopsis)
  : Synopsis(std::move(synopsis))
{
  this->Parser.Initialize(argc, argv);
  this->Given.assign(argv, argv + argc);
  this->Parser.StoreUnusedArguments(true);
  this->Parser.AddBooleanArgument("--help", &this->Help, "Print this help and exit.");
}

void Arguments::Flag(const char* name, bool* value, const char* help)
{
  this->Parser.AddBooleanArgument(name, value, help);
}

void Arguments::Option(const char* name, int* value, const char* help)
{
  this->Numbers.push_back({ this, value, true });
  this->Parser.AddCallback(name, vtksys::CommandLineArguments::SPACE_ARGUMENT,
    &Arguments::ParseNumber, &this->Numbers.back(), help);
}

void Arguments::Option(const char* name, double* value, const char* help)
{
  this->Numbers.push_back({ this, value, false });
  this->Parser.AddCallback(name, vtksys::CommandLineArguments::SPACE_ARGUMENT,
    &Arguments::ParseNumber, &this->Numbers.back(), help);
}

void Arguments::Option(const char* name, std::string* value, const char* help)
{
  this->Parser.AddArgument(name, vtksys::CommandLineArguments::SPACE_ARGUMENT, value, help);
}

const char* Arguments::Keep(std::string help)
{
  this->HelpTexts.push_back(std::move(help));
  return this->HelpTexts.back().c_str();
}

void Arguments::Positional(std::vector<std::string>* values, std::size_t count, const char* what)
{
  this->PositionalValues = values;
  this->PositionalCount = count;
  this->PositionalHelp = what;
}

int Arguments::ParseNumber(const char* argument, const char* value, void* data)
{
  auto* number = static_cast<Number*>(data);
  char* end = nullptr;
  errno = 0;
  if (number->Integer)
  {
    const long parsed = value ? std::strtol(value, &end, 10) : 0;
    *static_cast<int*>(number->Value) = static_cast<int>(parsed);
  }
  else
  {
    *static_cast<double*>(number->Value) = value ? std::strtod(value, &end) : 0.0;
  }
  if (!value || end == value || *end != '\0' || errno != 0)
  {
    number->Owner->Error = std::string(argument) + " needs " +
                           (number->Integer ? "an integer" : "a number") + ", not '" +
                           (value ? value : "") + "'";
    return 0;
  }
  return 1;
}

bool Arguments::Parse()
{
  const bool parsed = this->Parser.Parse() != 0;
  if (this->Help)
  {
    std::printf("%s\n\n", this->Synopsis.c_str());
    if (this->PositionalCount > 0)
    {
      std::printf("Arguments:\n  %s\n\n", this->PositionalHelp.c_str());
    }
    std::printf("Flags:\n%s", this->Parser.GetHelp());
    this->Code = EXIT_SUCCESS;
    return false;
  }
  int count = 0;
  char** unused = nullptr;
  this->Parser.GetUnusedArguments(&count, &unused);
  for (int i = 1; i < count && this->Error.empty(); ++i)
  {
    const std::string argument = unused[i];
    if (!argument.empty() && argument[0] == '-')
    {
      this->Error = "unknown flag " + argument;
    }
    else if (this->PositionalValues && this->PositionalValues->size() < this->PositionalCount)
    {
      this->PositionalValues->push_back(argument);
    }
    else
    {
      this->Error = "unexpected argument '" + argument + "'";
    }
  }
  this->Parser.DeleteRemainingArguments(count, &unused);
  if (!parsed && this->Error.empty())
  {
    // The parser stops at a flag whose value is missing.
    const unsigned int next = this->Parser.GetLastArgument() + 1;
    this->Error = next < this->Given.size() ? this->Given[next] + " needs a value"
                                                : std::string("cannot read the flags");
  }
  if (!this->Error.empty())
  {
    std::fprintf(
      stderr, "%s: %s (--help lists the flags)\n", this->Parser.GetArgv0(), this->Error.c_str());
    this->Code = EXIT_FAILURE;
    return false;
  }
  return true;
}

} // namespace savr_scenes
