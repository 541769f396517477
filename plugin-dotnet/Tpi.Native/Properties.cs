using System.Runtime.CompilerServices;

[assembly: InternalsVisibleTo("Tpi.Tests")]
